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

}  // namespace

Relighter::Relighter(const RayTracer& tracer, const SampleSet& samples, const PatchSet& patches,
                     const StoredTransport& transport, const RelighterSettings& settings,
                     Diagnostics* diagnostics)
    : multiplier_(timed_multiplier(transport, settings, diagnostics, multiply_seconds_)),
      compile_start_(Clock::now()),
      frame_(tracer, samples, patches, multiplier_.multiply_into(), settings.frame) {
  compile_seconds_ = since(compile_start_);
}

void Relighter::light(const std::vector<Light>& lights, const std::vector<AreaLight>& area) {
  frame_.solve(lights, area);
}

void Relighter::reflected(std::vector<glm::vec3>& out) const {
  const std::size_t n = frame_.size();
  out.resize(n);
  if (frame_.first_hit().size() == n && frame_.indirect().size() == n) {
    for (std::size_t p = 0; p < n; ++p) out[p] = frame_.first_hit()[p] + frame_.indirect()[p];
    return;
  }
  // The record holds E, b, T b per patch (3 x 3 floats).
  const std::vector<float>& record = frame_.record();
  if (record.size() != 9 * n)
    throw Error("relighter", "the frame neither publishes nor records b and T b");
  for (std::size_t p = 0; p < n; ++p) {
    const float* r = record.data() + 9 * p;
    out[p] = glm::vec3(r[3], r[4], r[5]) + glm::vec3(r[6], r[7], r[8]);
  }
}

void Relighter::gather(const FinalGather& gather, std::vector<glm::vec3>& irradiance) const {
  std::vector<glm::vec3> light;
  reflected(light);
  gather.irradiance(light, irradiance);
}

}  // namespace bounce
