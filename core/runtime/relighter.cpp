#include "runtime/relighter.h"

#include "base/error.h"

namespace bounce {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

TransportMultiplier timed_multiplier(const StoredTransport& transport,
                                     const RelighterSettings& settings, Diagnostics* diagnostics,
                                     double& seconds) {
  const auto start = Clock::now();
  TransportMultiplier m(transport, settings.multiply, settings.loop, diagnostics);
  seconds = since(start);
  return m;
}

// The frame as the relighter runs it: it keeps each sample's direct
// irradiance, which a final gather with sample sources reads (a few bytes
// per sample), and spreads the samples' shadow rays like the near sources'.
RuntimeFrameSettings frame_settings(const RelighterSettings& settings) {
  RuntimeFrameSettings s = settings.frame;
  s.sample_irradiance = true;
  s.shadow_frames = settings.shadow_frames;
  return s;
}

}  // namespace

Relighter::Relighter(const RayTracer& tracer, const SampleSet& samples, const PatchSet& patches,
                     const StoredTransport& transport, const RelighterSettings& settings,
                     Diagnostics* diagnostics)
    : multiplier_(timed_multiplier(transport, settings, diagnostics, multiply_seconds_)),
      compile_start_(Clock::now()),
      tracer_(tracer),
      samples_(samples),
      patches_(patches),
      near_shadows_(settings.shadow_frames),
      gather_rows_(settings.shadow_frames),
      frame_(tracer, samples, patches, multiplier_.multiply_into(), frame_settings(settings)) {
  compile_seconds_ = since(compile_start_);
}

void Relighter::light(const std::vector<Light>& lights, const std::vector<AreaLight>& area) {
  frame_.solve(lights, area);
  reflected_fresh_ = sample_light_fresh_ = false;
  lights_ = lights;
  area_ = area;
}

void Relighter::first_hit_and_indirect(std::vector<glm::vec3>& b,
                                       std::vector<glm::vec3>& tb) const {
  const std::size_t n = frame_.size();
  if (frame_.first_hit().size() == n && frame_.indirect().size() == n) {
    b = frame_.first_hit();
    tb = frame_.indirect();
    return;
  }
  // The record holds E, b, T b per patch (3 x 3 floats).
  const std::vector<float>& record = frame_.record();
  if (record.size() != 9 * n)
    throw Error("relighter", "the frame neither publishes nor records b and T b");
  b.resize(n);
  tb.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    const float* r = record.data() + 9 * p;
    b[p] = glm::vec3(r[3], r[4], r[5]);
    tb[p] = glm::vec3(r[6], r[7], r[8]);
  }
}

void Relighter::reflected(std::vector<glm::vec3>& out) const {
  std::vector<glm::vec3> b, tb;
  first_hit_and_indirect(b, tb);
  out.resize(b.size());
  for (std::size_t p = 0; p < b.size(); ++p) out[p] = b[p] + tb[p];
}

void Relighter::source_light(const FinalGather& gather) const {
  // The buffers live with the Relighter (and the product's padded light
  // with the thread): a frame reuses the last frame's memory instead of
  // paging in megabytes (the near sources' light alone is 7 MB on Sponza).
  // Each is worked out once a frame: the vertices' and the probes' gathers
  // read the same light.
  if (!reflected_fresh_) {
    first_hit_and_indirect(first_hit_, indirect_);
    reflected_.resize(first_hit_.size());
    for (std::size_t p = 0; p < first_hit_.size(); ++p)
      reflected_[p] = first_hit_[p] + indirect_[p];
    reflected_fresh_ = true;
  }
  if (gather.samples > 0 && !sample_light_fresh_) {
    sample_exitance(samples_, patches_, frame_.sample_irradiance(), indirect_, sample_light_);
    sample_light_fresh_ = true;
  }
}

void Relighter::gather(const FinalGather& gather, std::vector<glm::vec3>& irradiance) const {
  source_light(gather);
  // With every row summed every frame (k = 1) the product goes straight to
  // the caller; else into the kept product, whose rows a frame leaves keep
  // their light, then copied out.
  const bool spread = gather_rows_.frames() > 1;
  if (spread && gathered_for_ != &gather) {
    gathered_.clear();
    gathered_for_ = &gather;
  }
  std::vector<glm::vec3>& out = spread ? gathered_ : irradiance;
  // The near sources' light goes straight into the product's buffer.
  gather.irradiance_lighting_near(reflected_, sample_light_, tracer_, lights_, area_, indirect_,
                                  out, &near_seconds_, &near_area_cache_, &near_shadows_,
                                  &gather_rows_, frame_.shadows_settled());
  if (spread) irradiance = gathered_;
}

void Relighter::gather_far(const FinalGather& gather, std::vector<glm::vec3>& irradiance) const {
  if (gather.near.size() > 0)
    throw Error("final gather", "gather_far() is for gathers without near sources");
  source_light(gather);
  gather.irradiance(reflected_, sample_light_, irradiance);
}

}  // namespace bounce
