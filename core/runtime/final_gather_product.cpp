// The final gather's work per frame: the light of its sample and near
// sources, and the sparse product from every source's light to the points
// (building the rows is final_gather_build.cpp, packing them
// final_gather_compact.cpp).
#include "runtime/final_gather.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include "base/error.h"
#include "runtime/direct_light.h"
#include "runtime/gather_row_loops.h"
#include "runtime/near_source_light.h"

namespace bounce {

namespace {

using gather_loops::PaddedLight;

// Rows of weighted sums over another light: out[r] = sum over k in
// [first[r], first[r + 1]) of weight[k] x from[index(k)], for every row that
// has entries (the others keep what out holds). A sample's spots and a
// patch's seen samples are both such rows.
template <typename Index>
void weighted_rows(const std::vector<std::uint32_t>& first, const std::vector<float>& weight,
                   const PaddedLight* from, Index index, PaddedLight* out) {
  const std::size_t rows = first.size() - 1;
#pragma omp parallel for schedule(static, 256)
  for (std::int64_t ri = 0; ri < static_cast<std::int64_t>(rows); ++ri) {
    const auto r = static_cast<std::size_t>(ri);
    if (first[r] == first[r + 1]) continue;
    PaddedLight sum{};
    for (std::uint32_t k = first[r]; k < first[r + 1]; ++k)
      for (int c = 0; c < 3; ++c) sum.c[c] += weight[k] * from[index(k)].c[c];
    out[r] = sum;
  }
}

// The padded light of every source the rows read: the patches', then each
// cluster's mean, then the samples', then the near sources'. `near_exitance`
// null: the caller has written the near sources' light already (the buffer
// sized for every source first). The near sources come first because the
// samples with spots take their light from them, and the patches with seen
// weights from their samples.
void pad_light(const FinalGather& g, const std::vector<glm::vec3>& patch_exitance,
               const std::vector<glm::vec3>& sample_exitance,
               const std::vector<glm::vec3>* near_exitance, std::vector<PaddedLight>& light) {
  const std::size_t patches = g.patches, clusters = g.clusters, samples = g.samples;
  light.resize(patches + clusters + samples + g.near.size());
  const auto copy_padded = [](const std::vector<glm::vec3>& from, PaddedLight* to) {
#pragma omp parallel for schedule(static, 4096)
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(from.size()); ++i) {
      const glm::vec3& v = from[static_cast<std::size_t>(i)];
      to[i] = PaddedLight{{v.x, v.y, v.z, 0.0f}};
    }
  };
  PaddedLight* const sample_light = light.data() + patches + clusters;
  PaddedLight* const near_light = sample_light + samples;
  if (near_exitance) copy_padded(*near_exitance, near_light);
  if (samples > 0) copy_padded(sample_exitance, sample_light);
  if (!g.spot_first.empty())
    weighted_rows(
        g.spot_first, g.spot_weight, near_light + g.spot_base(), [](std::uint32_t k) { return k; },
        sample_light);
  copy_padded(patch_exitance, light.data());
  if (samples > 0 && !g.seen_first.empty())
    weighted_rows(
        g.seen_first, g.seen_weight, sample_light,
        [&g](std::uint32_t k) { return g.seen_sample[k]; }, light.data());
  std::fill(light.begin() + static_cast<std::ptrdiff_t>(patches),
            light.begin() + static_cast<std::ptrdiff_t>(patches + clusters), PaddedLight{});
  for (std::size_t p = 0; p < patches; ++p) {
    PaddedLight& cl = light[patches + g.cluster_of_patch[p]];
    for (int c = 0; c < 3; ++c) cl.c[c] += g.cluster_share[p] * light[p].c[c];
  }
}

}  // namespace

void FinalGather::irradiance(const std::vector<glm::vec3>& patch_exitance,
                             std::vector<glm::vec3>& out) const {
  if (samples > 0)
    throw Error("final gather", "the gather reads samples: their light is needed too");
  irradiance(patch_exitance, {}, out);
}

void FinalGather::irradiance(const std::vector<glm::vec3>& patch_exitance,
                             const std::vector<glm::vec3>& sample_exitance,
                             std::vector<glm::vec3>& out) const {
  if (near.size() > 0)
    throw Error("final gather", "the gather reads near sources: their light is needed too");
  irradiance(patch_exitance, sample_exitance, {}, out);
}

void FinalGather::check_light(const std::vector<glm::vec3>& patch_exitance,
                              const std::vector<glm::vec3>& sample_exitance) const {
  if (patch_exitance.size() != patches)
    throw Error("final gather", "light for " + std::to_string(patch_exitance.size()) +
                                    " patches, the gather was made for " + std::to_string(patches));
  if (samples > 0 && sample_exitance.size() != samples)
    throw Error("final gather", "light for " + std::to_string(sample_exitance.size()) +
                                    " samples, the gather was made for " + std::to_string(samples));
}

// Each source's light padded to four floats: one 16-byte load then fetches
// its colour, and an entry costs one four-lane multiply-add. (Three separate
// floats made the compiler shuffle lanes for every entry: the product took
// three times as long as its memory traffic.) The buffer stays with the
// thread, so a frame does not page in megabytes of fresh memory.
namespace {
thread_local std::vector<PaddedLight> padded_light;
}  // namespace

void FinalGather::irradiance(const std::vector<glm::vec3>& patch_exitance,
                             const std::vector<glm::vec3>& sample_exitance,
                             const std::vector<glm::vec3>& near_exitance,
                             std::vector<glm::vec3>& out) const {
  if (near_exitance.size() != near.size())
    throw Error("final gather", "light for " + std::to_string(near_exitance.size()) +
                                    " near sources, the gather has " + std::to_string(near.size()));
  check_light(patch_exitance, sample_exitance);
  pad_light(*this, patch_exitance, sample_exitance, &near_exitance, padded_light);
  sum_padded(padded_light.data(), out);
}

void FinalGather::irradiance_lighting_near(
    const std::vector<glm::vec3>& patch_exitance, const std::vector<glm::vec3>& sample_exitance,
    const RayTracer& tracer, const std::vector<Light>& lights, const std::vector<AreaLight>& area,
    const std::vector<glm::vec3>& patch_indirect, std::vector<glm::vec3>& out, double* near_seconds,
    AreaLightCache* area_cache, ShadowBudget* shadow_budget, GatherRowBudget* row_budget,
    bool sources_exact) const {
  check_light(patch_exitance, sample_exitance);
  padded_light.resize(patches + clusters + samples + near.size());
  const auto start = std::chrono::steady_clock::now();
  if (near.size() > 0)
    light_near_sources(near, &tracer, lights, area, patch_indirect,
                       padded_light[patches + clusters + samples].c, 4, area_cache, shadow_budget);
  if (near_seconds)
    *near_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  pad_light(*this, patch_exitance, sample_exitance, nullptr, padded_light);
  RowSlice rows;
  if (row_budget) {
    const bool exact = sources_exact && (!shadow_budget || shadow_budget->settled());
    rows = row_budget->next(exact, out.size() != points());
  }
  sum_padded(padded_light.data(), out, rows);
}

void FinalGather::sum_padded(const PaddedLight* light, std::vector<glm::vec3>& out,
                             RowSlice slice) const {
  const std::size_t n = points();
  out.resize(n);
  if (compact.size() == source.size() && !compact.empty()) {
    gather_loops::sum_compact_rows(
        gather_loops::compact_loop(compact_loop.empty() ? "sse2" : compact_loop),
        gather_loops::CompactRows{light, first.data(), compact.data(), compact_count_bits,
                                  static_cast<float>(1.0 / compact_rays)},
        n, out.data(), slice);
    return;
  }
  const gather_loops::FloatEntries entries{light, source.data(), weight.data()};
#pragma omp parallel for schedule(static, 1024)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(n); ++i) {
    const auto row = static_cast<std::size_t>(i);
    if (slice.sums_band(row / kRowBand))
      out[row] = gather_loops::sum_row(entries, first[row], first[row + 1], 1.0f);
  }
}

std::vector<glm::vec3> sample_exitance(const SampleSet& samples, const PatchSet& patches,
                                       const std::vector<glm::vec3>& sample_irradiance,
                                       const std::vector<glm::vec3>& patch_indirect) {
  std::vector<glm::vec3> out;
  sample_exitance(samples, patches, sample_irradiance, patch_indirect, out);
  return out;
}

void sample_exitance(const SampleSet& samples, const PatchSet& patches,
                     const std::vector<glm::vec3>& sample_irradiance,
                     const std::vector<glm::vec3>& patch_indirect, std::vector<glm::vec3>& out) {
  const std::size_t n = samples.samples.size();
  if (sample_irradiance.size() != n || patch_indirect.size() != patches.size())
    throw Error("final gather", "one irradiance per sample and one T b per patch expected");
  out.assign(n, glm::vec3(0.0f));
  // On the threads: a serial pass over Sponza's 44,396 samples took a third
  // of a millisecond a frame.
#pragma omp parallel for schedule(static, 256)
  for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(patches.size()); ++pi) {
    const auto p = static_cast<std::size_t>(pi);
    for (std::uint32_t k = patches.member_first[p]; k < patches.member_first[p + 1]; ++k) {
      const std::uint32_t s = patches.member_samples[k];
      out[s] = samples.samples[s].albedo * sample_irradiance[s] + patch_indirect[p];
    }
  }
}

std::vector<glm::vec3> near_exitance(const NearSources& near, const RayTracer* tracer,
                                     const std::vector<Light>& lights,
                                     const std::vector<AreaLight>& area,
                                     const std::vector<glm::vec3>& patch_indirect) {
  std::vector<glm::vec3> out;
  near_exitance(near, tracer, lights, area, patch_indirect, out);
  return out;
}

void near_exitance(const NearSources& near, const RayTracer* tracer,
                   const std::vector<Light>& lights, const std::vector<AreaLight>& area,
                   const std::vector<glm::vec3>& patch_indirect, std::vector<glm::vec3>& out) {
  // Every source is written: resizing keeps a reused buffer's pages.
  out.resize(near.size());
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  light_near_sources(near, tracer, lights, area, patch_indirect, out.empty() ? nullptr : &out[0].x,
                     3);
}

}  // namespace bounce
