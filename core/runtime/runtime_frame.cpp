#include "runtime/runtime_frame.h"

#include <chrono>
#include <cstdint>
#include <utility>

#include "base/error.h"
#include "runtime/direct_light.h"

namespace bounce {

RuntimeFrame::RuntimeFrame(const RayTracer& tracer, const SampleSet& samples,
                           const PatchSet& patches, IndirectMultiply multiply,
                           RuntimeFrameSettings settings)
    : tracer_(tracer),
      samples_(samples),
      patches_(patches),
      multiply_(std::move(multiply)),
      settings_(settings),
      n_(patches.size()) {
  if (!multiply_) throw Error("runtime frame", "no indirect multiply given");
  if (n_ > 0 && patches_.member_first.size() != n_ + 1)
    throw Error("runtime frame", "the patch set has " + std::to_string(n_) + " patches but " +
                                     std::to_string(patches_.member_first.size()) +
                                     " member offsets");
  if (n_ > 0 && patches_.member_first.back() > patches_.member_samples.size())
    throw Error("runtime frame", "the patch set's member offsets run past its " +
                                     std::to_string(patches_.member_samples.size()) + " members");
  for (std::uint32_t s : patches_.member_samples)
    if (s >= samples_.samples.size())
      throw Error("runtime frame", "a patch member is sample " + std::to_string(s) + " of " +
                                       std::to_string(samples_.samples.size()) +
                                       ": the samples are not the patches' own");
  if (settings_.area_strata < 1) throw Error("runtime frame", "area_strata must be at least 1");

  // Persistent buffers, sized once: the multiplies fill the vectors they are
  // given and resize them only when the size differs.
  const std::size_t colour = n_ * sizeof(glm::vec3);
  first_hit_.assign(n_, glm::vec3(0.0f));
  indirect_.assign(n_, glm::vec3(0.0f));
  exitance_.assign(n_, glm::vec3(0.0f));
  if (settings_.record) record_.assign(n_ * 9, 0.0f);

  const auto lights = graph_.add_imported("lights", nullptr, 0);
  const auto transport = graph_.add_imported("T", nullptr, 0);
  const auto e = graph_.add_transient("E", colour);
  const auto b = graph_.add_imported("b", first_hit_.data(), colour);
  const auto tb = graph_.add_imported("T b", indirect_.data(), colour);
  const auto out = graph_.add_imported("exitance", exitance_.data(), colour);
  const auto record = settings_.record ? graph_.add_imported("record", record_.data(),
                                                             record_.size() * sizeof(float))
                                       : FrameGraph::ResourceId{};

  add_timed_pass("direct light", {lights}, {e}, [this, e](const FrameGraph::Context& c) {
    // As direct_irradiance(), into the arena: the area-weighted mean of the
    // irradiance at the patch's member samples.
    glm::vec3* irradiance = c.get<glm::vec3>(e);
#pragma omp parallel for schedule(dynamic, 16)
    for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(n_); ++pi) {
      const auto p = static_cast<std::size_t>(pi);
      glm::vec3 sum(0.0f);
      float area = 0.0f;
      for (std::uint32_t k = patches_.member_first[p]; k < patches_.member_first[p + 1]; ++k) {
        const std::uint32_t index = patches_.member_samples[k];
        const Sample& s = samples_.samples[index];
        sum += s.area * irradiance_at(tracer_, s.position, s.normal, *lights_, *area_,
                                      settings_.area_strata, index);
        area += s.area;
      }
      irradiance[p] = area > 0.0f ? sum / area : glm::vec3(0.0f);
    }
  });
  add_timed_pass("first hit", {e}, {b}, [this, e](const FrameGraph::Context& c) {
    const glm::vec3* irradiance = c.get<glm::vec3>(e);
    for (std::size_t p = 0; p < n_; ++p) first_hit_[p] = patches_.patches[p].albedo * irradiance[p];
  });
  if (settings_.record)
    add_timed_pass("record direct", {e, b}, {record}, [this, e](const FrameGraph::Context& c) {
      const glm::vec3* irradiance = c.get<glm::vec3>(e);
      for (std::size_t p = 0; p < n_; ++p)
        for (int k = 0; k < 3; ++k) {
          record_[9 * p + static_cast<std::size_t>(k)] = irradiance[p][k];
          record_[9 * p + 3 + static_cast<std::size_t>(k)] = first_hit_[p][k];
        }
    });
  add_timed_pass("indirect product", {transport, b}, {tb},
                 [this](const FrameGraph::Context&) { multiply_(first_hit_, indirect_); });
  add_timed_pass("apply", {b, tb}, {out}, [this](const FrameGraph::Context&) {
    if (indirect_.size() != n_)
      throw Error("runtime frame", "the multiply returned " + std::to_string(indirect_.size()) +
                                       " values for " + std::to_string(n_) + " patches");
    for (std::size_t p = 0; p < n_; ++p)
      exitance_[p] = patches_.patches[p].emission + first_hit_[p] + indirect_[p];
  });
  if (settings_.record)
    add_timed_pass("record indirect", {tb}, {record}, [this](const FrameGraph::Context&) {
      for (std::size_t p = 0; p < n_; ++p)
        for (int k = 0; k < 3; ++k)
          record_[9 * p + 6 + static_cast<std::size_t>(k)] = indirect_[p][k];
    });
  graph_.compile(settings_.alias);
}

void RuntimeFrame::add_timed_pass(std::string name, std::vector<FrameGraph::ResourceId> reads,
                                  std::vector<FrameGraph::ResourceId> writes,
                                  FrameGraph::PassFunction run) {
  const std::size_t slot = pass_seconds_.size();
  pass_seconds_.push_back(0.0);
  graph_.add_pass(std::move(name), std::move(reads), std::move(writes),
                  [this, slot, run = std::move(run)](const FrameGraph::Context& c) {
                    const auto t = std::chrono::steady_clock::now();
                    run(c);
                    pass_seconds_[slot] =
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
                  });
}

void RuntimeFrame::solve(const std::vector<Light>& lights, const std::vector<AreaLight>& area) {
  lights_ = &lights;
  area_ = &area;
  graph_.execute();
  lights_ = nullptr;
  area_ = nullptr;
}

}  // namespace bounce
