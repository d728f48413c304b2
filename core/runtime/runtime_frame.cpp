#include "runtime/runtime_frame.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>

#include "base/error.h"
#include "runtime/direct_light.h"
#include "runtime/seen_first_hit.h"

namespace bounce {

namespace {

// A vector multiply behind the span interface: b is copied into a scratch
// vector and T b out of one (both sized on the first frame, then reused).
IndirectMultiplySpan through_vectors(IndirectMultiply multiply) {
  if (!multiply) return {};
  struct Scratch {
    std::vector<glm::vec3> in, out;
  };
  auto scratch = std::make_shared<Scratch>();
  return [multiply = std::move(multiply), scratch](std::span<const glm::vec3> b,
                                                   std::span<glm::vec3> indirect) {
    scratch->in.assign(b.begin(), b.end());
    multiply(scratch->in, scratch->out);
    if (scratch->out.size() != indirect.size())
      throw Error("runtime frame", "the multiply returned " + std::to_string(scratch->out.size()) +
                                       " values for " + std::to_string(indirect.size()) +
                                       " patches");
    std::copy(scratch->out.begin(), scratch->out.end(), indirect.begin());
  };
}

}  // namespace

RuntimeFrame::RuntimeFrame(const RayTracer& tracer, const SampleSet& samples,
                           const PatchSet& patches, IndirectMultiply multiply,
                           RuntimeFrameSettings settings)
    : RuntimeFrame(tracer, samples, patches, through_vectors(std::move(multiply)), settings) {}

RuntimeFrame::RuntimeFrame(const RayTracer& tracer, const SampleSet& samples,
                           const PatchSet& patches, IndirectMultiplySpan multiply,
                           RuntimeFrameSettings settings)
    : tracer_(tracer),
      samples_(samples),
      patches_(patches),
      multiply_(std::move(multiply)),
      settings_(settings),
      n_(patches.size()),
      frames_(carried_polygon_frames(samples)) {
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
  if (settings_.shadow_frames < 1) throw Error("runtime frame", "shadow_frames must be at least 1");
  if (settings_.shadow_frames > 1) shadows_.emplace(settings_.shadow_frames);
  build();
}

void RuntimeFrame::build() {
  // Persistent outputs, sized once.
  const std::size_t colour = n_ * sizeof(glm::vec3);
  exitance_.assign(n_, glm::vec3(0.0f));
  if (settings_.publish) {
    first_hit_.assign(n_, glm::vec3(0.0f));
    indirect_.assign(n_, glm::vec3(0.0f));
  }
  if (settings_.record) record_.assign(n_ * 9, 0.0f);
  // Seen weights make b from each sample's own E (runtime/seen_first_hit.h).
  if (!patches_.member_seen_weight.empty()) settings_.sample_irradiance = true;
  if (settings_.sample_irradiance)
    sample_irradiance_.assign(samples_.samples.size(), glm::vec3(0.0f));

  const auto lights = graph_.add_imported("lights", nullptr, 0);
  const auto transport = graph_.add_imported("T", nullptr, 0);
  const auto e = graph_.add_transient("E", colour);
  const auto b = graph_.add_transient("b", colour);
  const auto tb = graph_.add_transient("T b", colour);
  const auto out = graph_.add_imported("exitance", exitance_.data(), colour);
  const auto record = settings_.record ? graph_.add_imported("record", record_.data(),
                                                             record_.size() * sizeof(float))
                                       : FrameGraph::ResourceId{};
  const std::size_t n = n_;
  const auto span = [n](const FrameGraph::Context& c, FrameGraph::ResourceId id) {
    return std::span<glm::vec3>(c.get<glm::vec3>(id), n);
  };

  std::vector<FrameGraph::ResourceId> direct_writes{e};
  if (settings_.sample_irradiance)
    direct_writes.push_back(graph_.add_imported("E per sample", sample_irradiance_.data(),
                                                sample_irradiance_.size() * sizeof(glm::vec3)));
  add_timed_pass("direct light", {lights}, direct_writes,
                 [this, e, span](const FrameGraph::Context& c) {
                   direct_irradiance(tracer_, samples_, frames_, patches_, *lights_, *area_,
                                     settings_.area_strata, span(c, e), sample_irradiance_,
                                     &area_cache_, shadows_ ? &*shadows_ : nullptr);
                 });
  add_timed_pass("first hit", {e}, {b}, [this, e, b, span](const FrameGraph::Context& c) {
    seen_first_hit(samples_, patches_, span(c, e), sample_irradiance_, span(c, b));
  });
  if (settings_.record)
    add_timed_pass("record direct", {e, b}, {record},
                   [this, e, b, span](const FrameGraph::Context& c) {
                     const auto irradiance = span(c, e);
                     const auto first_hit = span(c, b);
                     for (std::size_t p = 0; p < n_; ++p)
                       for (int k = 0; k < 3; ++k) {
                         record_[9 * p + static_cast<std::size_t>(k)] = irradiance[p][k];
                         record_[9 * p + 3 + static_cast<std::size_t>(k)] = first_hit[p][k];
                       }
                   });
  add_timed_pass(
      "indirect product", {transport, b}, {tb},
      [this, b, tb, span](const FrameGraph::Context& c) { multiply_(span(c, b), span(c, tb)); });
  add_timed_pass("apply", {b, tb}, {out}, [this, b, tb, span](const FrameGraph::Context& c) {
    const auto first_hit = span(c, b);
    const auto indirect = span(c, tb);
    for (std::size_t p = 0; p < n_; ++p)
      exitance_[p] = patches_.patches[p].emission + first_hit[p] + indirect[p];
  });
  if (settings_.record)
    add_timed_pass("record indirect", {tb}, {record},
                   [this, tb, span](const FrameGraph::Context& c) {
                     const auto indirect = span(c, tb);
                     for (std::size_t p = 0; p < n_; ++p)
                       for (int k = 0; k < 3; ++k)
                         record_[9 * p + 6 + static_cast<std::size_t>(k)] = indirect[p][k];
                   });
  if (settings_.publish) {
    const auto b_out = graph_.add_imported("first hit (published)", first_hit_.data(), colour);
    const auto tb_out = graph_.add_imported("T b (published)", indirect_.data(), colour);
    add_timed_pass("publish", {b, tb}, {b_out, tb_out},
                   [this, b, tb, span](const FrameGraph::Context& c) {
                     const auto first_hit = span(c, b);
                     const auto indirect = span(c, tb);
                     std::copy(first_hit.begin(), first_hit.end(), first_hit_.begin());
                     std::copy(indirect.begin(), indirect.end(), indirect_.begin());
                   });
  }
  graph_.set_poison_dead_transients(settings_.poison_dead_transients);
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
  last_light_count_ = lights.size();
}

std::size_t RuntimeFrame::traced_shadow_batches() const {
  return shadows_ ? shadows_->traced_batches() : last_light_count_ * n_;
}

}  // namespace bounce
