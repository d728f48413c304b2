// The final gather's work per frame: the light of its sample and near
// sources, and the sparse product from every source's light to the points
// (building the rows is final_gather.cpp).
#include "runtime/final_gather.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>

#include "base/error.h"
#include "runtime/direct_light.h"
#include "runtime/gather_row_loops.h"

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

// The near sources' light (see near_exitance()) written to out[i * stride],
// three floats each (and a zero fourth when stride is 4, the product's
// padded light).
void light_near_sources(const NearSources& near, const RayTracer* tracer,
                        const std::vector<Light>& lights, const std::vector<AreaLight>& area,
                        const std::vector<glm::vec3>& patch_indirect, float* out,
                        std::size_t stride);

gather_loops::CompactRows compact_rows_of(const FinalGather& g,
                                          const std::vector<PaddedLight>& light) {
  return {light.data(), g.first.data(), g.compact.data(), g.compact_count_bits,
          static_cast<float>(1.0 / g.compact_rays)};
}

// Which compact loop sums these rows fastest: each runs the whole product
// once to warm its caches, then three times timed, and the fastest time
// counts. Which is fastest depends on the CPU (how it splits wide
// instructions, how many loads it issues a cycle) more than on its feature
// flags, so it is measured on the rows themselves.
//
// Only loops that give the same light compete: the fused ones where this CPU
// has them, else the portable one. (Between the portable and a fused loop a
// timing race would decide the last bits of the light, and two processes
// lighting the same bake could disagree.)
std::string fastest_compact_loop(const FinalGather& g) {
  std::vector<gather_loops::CompactLoop> loops = gather_loops::compact_loops();
  if (std::any_of(loops.begin(), loops.end(), [](const auto& l) { return l.fused; }))
    std::erase_if(loops, [](const auto& l) { return !l.fused; });
  if (loops.size() == 1) return loops.front().name;
  std::vector<PaddedLight> light(g.patches + g.clusters + g.samples + g.near.size(),
                                 PaddedLight{{1.0f, 1.0f, 1.0f, 0.0f}});
  const gather_loops::CompactRows rows = compact_rows_of(g, light);
  std::vector<glm::vec3> out(g.points());
  using Clock = std::chrono::steady_clock;
  std::string best_name;
  double best = std::numeric_limits<double>::infinity();
  for (const gather_loops::CompactLoop& loop : loops)
    for (int run = 0; run < 4; ++run) {
      const auto start = Clock::now();
      gather_loops::sum_compact_rows(loop, rows, g.points(), out.data());
      const double t = std::chrono::duration<double>(Clock::now() - start).count();
      if (run > 0 && t < best) {
        best = t;
        best_name = loop.name;
      }
    }
  return best_name;
}

}  // namespace

void FinalGather::compact_rows() {
  compact.clear();
  compact_loop.clear();
  compact_count_bits = 0;
  compact_rays = 0;
  if (source.empty() || source.size() != weight.size()) return;
  // The rays per point: the build's `rays`, or (rows read from a bake) the
  // one a smallest weight of one ray gives.
  int r = rays;
  if (r <= 0) {
    float smallest = 1.0f;
    for (const float x : weight)
      if (x > 0.0f) smallest = std::min(smallest, x);
    const double guess = std::round(1.0 / static_cast<double>(smallest));
    if (!(guess >= 1.0 && guess <= 65536.0)) return;
    r = static_cast<int>(guess);
  }
  const int bits = std::bit_width(static_cast<unsigned>(r));
  if (bits >= 32) return;
  const std::uint64_t max_source = (std::uint64_t{1} << (32 - bits)) - 1;
  const double per_ray = 1.0 / static_cast<double>(r);
  std::vector<std::uint32_t> c(source.size());
  for (std::size_t k = 0; k < source.size(); ++k) {
    const double count = std::round(static_cast<double>(weight[k]) * r);
    // The weight must be exactly what the build stores for that count.
    if (!(count >= 0.0 && count <= r) || source[k] > max_source ||
        static_cast<float>(per_ray * count) != weight[k])
      return;
    c[k] = source[k] << bits | static_cast<std::uint32_t>(count);
  }
  compact = std::move(c);
  compact_count_bits = bits;
  compact_rays = r;
  compact_loop = fastest_compact_loop(*this);
}

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
    const std::vector<glm::vec3>& patch_indirect, std::vector<glm::vec3>& out,
    double* near_seconds) const {
  check_light(patch_exitance, sample_exitance);
  padded_light.resize(patches + clusters + samples + near.size());
  const auto start = std::chrono::steady_clock::now();
  if (near.size() > 0)
    light_near_sources(near, &tracer, lights, area, patch_indirect,
                       padded_light[patches + clusters + samples].c, 4);
  if (near_seconds)
    *near_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  pad_light(*this, patch_exitance, sample_exitance, nullptr, padded_light);
  sum_padded(padded_light.data(), out);
}

void FinalGather::sum_padded(const PaddedLight* light, std::vector<glm::vec3>& out) const {
  const std::size_t n = points();
  out.resize(n);
  if (compact.size() == source.size() && !compact.empty()) {
    gather_loops::sum_compact_rows(
        gather_loops::compact_loop(compact_loop.empty() ? "sse2" : compact_loop),
        gather_loops::CompactRows{light, first.data(), compact.data(), compact_count_bits,
                                  static_cast<float>(1.0 / compact_rays)},
        n, out.data());
    return;
  }
  const gather_loops::FloatEntries entries{light, source.data(), weight.data()};
#pragma omp parallel for schedule(static, 1024)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(n); ++i) {
    const auto row = static_cast<std::size_t>(i);
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

namespace {

void light_near_sources(const NearSources& near, const RayTracer* tracer,
                        const std::vector<Light>& lights, const std::vector<AreaLight>& area,
                        const std::vector<glm::vec3>& patch_indirect, float* out,
                        std::size_t stride) {
  const std::size_t n = near.size();
  // The first source naming a patch that is not there, checked on the
  // threads as each source is written (n: none).
  std::atomic<std::size_t> first_bad{n};
  const float eps = tracer ? 10.0f * tracer->epsilon() : 0.0f;
  const std::size_t first_spot = n - std::min(n, near.spot_count);
  // The shadow rays to one light go to Embree in batches of a few hundred
  // (its stream API): on Sponza's 421,838 near sources and the sun 1.5
  // times as fast as one rtcOccluded1 call per ray. (Marking the batches
  // coherent, or sending them as packets of 8 or 16, measured no faster.)
  // Each source sums its lights in order, then the area lights, as
  // irradiance_at() does, so the light is the same to the last bit.
  constexpr std::size_t kBatch = 256;
  const std::size_t batches = (n + kBatch - 1) / kBatch;
  std::vector<LightReach> reach;
  for (const Light& light : lights) reach.emplace_back(light);
#pragma omp parallel
  {
    // A batch's rays to one light, their unshadowed light and whose they
    // are: written field by field in place (see LightReach::at).
    std::vector<ShadowRay> rays(kBatch);
    std::vector<glm::vec3> value(kBatch), e;
    std::vector<std::uint32_t> who(kBatch);
    std::vector<std::uint8_t> blocked(kBatch);
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t bi = 0; bi < static_cast<std::int64_t>(batches); ++bi) {
      const std::size_t lo = static_cast<std::size_t>(bi) * kBatch, hi = std::min(n, lo + kBatch);
      e.assign(hi - lo, glm::vec3(0.0f));
      if (tracer) {
        for (const LightReach& light : reach) {
          std::size_t m = 0;
          for (std::size_t i = lo; i < hi; ++i) {
            // Lifted once here and once more by the light's own offset, as
            // irradiance_at() lifts the point it is given.
            const glm::vec3 at = near.position[i] + eps * near.normal[i];
            if (light.at(at, near.normal[i], eps, rays[m], value[m]))
              who[m++] = static_cast<std::uint32_t>(i - lo);
          }
          tracer->occluded(rays.data(), m, blocked.data());
          for (std::size_t k = 0; k < m; ++k)
            if (!blocked[k]) e[who[k]] += value[k];
        }
        for (const AreaLight& light : area)
          for (std::size_t i = lo; i < hi; ++i)
            e[i - lo] += area_light_irradiance(*tracer, near.position[i] + eps * near.normal[i],
                                               near.normal[i], light, i >= first_spot ? 1 : 4, i);
      }
      for (std::size_t i = lo; i < hi; ++i) {
        const bool known = near.patch[i] < patch_indirect.size();
        const glm::vec3 v =
            known ? near.albedo[i] * e[i - lo] + patch_indirect[near.patch[i]] : glm::vec3(0.0f);
        float* o = out + i * stride;
        o[0] = v.x;
        o[1] = v.y;
        o[2] = v.z;
        if (stride == 4) o[3] = 0.0f;
        if (!known)
          for (std::size_t seen = first_bad.load();
               i < seen && !first_bad.compare_exchange_weak(seen, i);) {
          }
      }
    }
  }
  if (const std::size_t i = first_bad.load(); i < n)
    throw Error("final gather", "near source " + std::to_string(i) + " names patch " +
                                    std::to_string(near.patch[i]) + " of " +
                                    std::to_string(patch_indirect.size()));
}

}  // namespace

}  // namespace bounce
