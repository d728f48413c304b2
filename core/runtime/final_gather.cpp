#include "runtime/final_gather.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>
#include <unordered_map>

#include "base/error.h"
#include "base/random.h"
#include "raytrace/cosine_lattice.h"
#include "runtime/direct_light.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace bounce {

namespace {

// A source's light, padded to 16 bytes.
struct alignas(16) PaddedLight {
  float c[4] = {0.0f, 0.0f, 0.0f, 0.0f};
};

// sum_k w[k] light[src[k]] over one row's entries [begin, end).
glm::vec3 gather_row(const PaddedLight* light, const std::uint32_t* src, const float* w,
                     std::uint64_t begin, std::uint64_t end) {
#if defined(__SSE2__)
  // Two sums, so that consecutive entries do not wait on each other's add.
  __m128 e0 = _mm_setzero_ps(), e1 = _mm_setzero_ps();
  std::uint64_t k = begin;
  for (; k + 2 <= end; k += 2) {
    e0 = _mm_add_ps(e0, _mm_mul_ps(_mm_set1_ps(w[k]), _mm_load_ps(light[src[k]].c)));
    e1 = _mm_add_ps(e1, _mm_mul_ps(_mm_set1_ps(w[k + 1]), _mm_load_ps(light[src[k + 1]].c)));
  }
  if (k < end) e0 = _mm_add_ps(e0, _mm_mul_ps(_mm_set1_ps(w[k]), _mm_load_ps(light[src[k]].c)));
  alignas(16) float e[4];
  _mm_store_ps(e, _mm_add_ps(e0, e1));
  return glm::vec3(e[0], e[1], e[2]);
#else
  glm::vec3 e(0.0f);
  for (std::uint64_t k = begin; k < end; ++k)
    e += w[k] * glm::vec3(light[src[k]].c[0], light[src[k]].c[1], light[src[k]].c[2]);
  return e;
#endif
}

// The same over compact entries: sum_k count_k light[source_k], the ray
// counts' sum scaled by 1 / rays once at the end.
glm::vec3 gather_compact_row(const PaddedLight* light, const std::uint32_t* entry, int count_bits,
                             float per_ray, std::uint64_t begin, std::uint64_t end) {
  const std::uint32_t count_mask = (1u << count_bits) - 1u;
#if defined(__SSE2__)
  const auto term = [&](std::uint32_t v) {
    return _mm_mul_ps(_mm_set1_ps(static_cast<float>(v & count_mask)),
                      _mm_load_ps(light[v >> count_bits].c));
  };
  __m128 e0 = _mm_setzero_ps(), e1 = _mm_setzero_ps();
  std::uint64_t k = begin;
  for (; k + 2 <= end; k += 2) {
    e0 = _mm_add_ps(e0, term(entry[k]));
    e1 = _mm_add_ps(e1, term(entry[k + 1]));
  }
  if (k < end) e0 = _mm_add_ps(e0, term(entry[k]));
  alignas(16) float e[4];
  _mm_store_ps(e, _mm_mul_ps(_mm_set1_ps(per_ray), _mm_add_ps(e0, e1)));
  return glm::vec3(e[0], e[1], e[2]);
#else
  glm::vec3 e(0.0f);
  for (std::uint64_t k = begin; k < end; ++k) {
    const PaddedLight& l = light[entry[k] >> count_bits];
    e += static_cast<float>(entry[k] & count_mask) * glm::vec3(l.c[0], l.c[1], l.c[2]);
  }
  return per_ray * e;
#endif
}

}  // namespace

void FinalGather::compact_rows() {
  compact.clear();
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

void FinalGather::irradiance(const std::vector<glm::vec3>& patch_exitance,
                             const std::vector<glm::vec3>& sample_exitance,
                             const std::vector<glm::vec3>& near_exitance,
                             std::vector<glm::vec3>& out) const {
  if (near_exitance.size() != near.size())
    throw Error("final gather", "light for " + std::to_string(near_exitance.size()) +
                                    " near sources, the gather has " + std::to_string(near.size()));
  if (patch_exitance.size() != patches)
    throw Error("final gather", "light for " + std::to_string(patch_exitance.size()) +
                                    " patches, the gather was made for " + std::to_string(patches));
  if (samples > 0 && sample_exitance.size() != samples)
    throw Error("final gather", "light for " + std::to_string(sample_exitance.size()) +
                                    " samples, the gather was made for " + std::to_string(samples));
  // The patches' light, then each cluster's area-weighted mean, then the
  // samples', then the near sources', each padded to four floats: one
  // 16-byte load then fetches a source's colour, and an entry costs one
  // four-lane multiply-add. (Three separate floats made the compiler shuffle
  // lanes for every entry: the product took three times as long as its
  // memory traffic.) The buffer stays with the thread, so a frame does not
  // page in megabytes of fresh memory.
  const std::size_t sources = patches + clusters + samples + near.size();
  thread_local std::vector<PaddedLight> light;
  light.resize(sources);
  std::fill(light.begin() + static_cast<std::ptrdiff_t>(patches),
            light.begin() + static_cast<std::ptrdiff_t>(patches + clusters), PaddedLight{});
  for (std::size_t p = 0; p < patches; ++p) {
    PaddedLight& cl = light[patches + cluster_of_patch[p]];
    for (int c = 0; c < 3; ++c) cl.c[c] += cluster_share[p] * patch_exitance[p][c];
  }
  // The rest is a copy per source, spread over the threads.
  const std::size_t sample_base = patches + clusters, near_base = sample_base + samples;
  PaddedLight* to = light.data();
#pragma omp parallel for schedule(static, 4096)
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(sources); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    glm::vec3 v;
    if (i < patches)
      v = patch_exitance[i];
    else if (i < sample_base)
      continue;
    else if (i < near_base)
      v = sample_exitance[i - sample_base];
    else
      v = near_exitance[i - near_base];
    to[i] = PaddedLight{{v.x, v.y, v.z, 0.0f}};
  }
  const std::size_t n = points();
  out.resize(n);
  const PaddedLight* b = light.data();
  if (compact.size() == source.size() && !compact.empty()) {
    const std::uint32_t* entry = compact.data();
    const int bits = compact_count_bits;
    const float per_ray = static_cast<float>(1.0 / compact_rays);
#pragma omp parallel for schedule(static, 1024)
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(n); ++i) {
      const auto row = static_cast<std::size_t>(i);
      out[row] = gather_compact_row(b, entry, bits, per_ray, first[row], first[row + 1]);
    }
    return;
  }
  const std::uint32_t* src = source.data();
  const float* w = weight.data();
#pragma omp parallel for schedule(static, 1024)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(n); ++i) {
    const auto row = static_cast<std::size_t>(i);
    out[row] = gather_row(b, src, w, first[row], first[row + 1]);
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
  for (std::size_t p = 0; p < patches.size(); ++p)
    for (std::uint32_t k = patches.member_first[p]; k < patches.member_first[p + 1]; ++k) {
      const std::uint32_t s = patches.member_samples[k];
      out[s] = samples.samples[s].albedo * sample_irradiance[s] + patch_indirect[p];
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
  const std::size_t n = near.size();
  // Every source is written below: resizing keeps a reused buffer's pages.
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    if (near.patch[i] >= patch_indirect.size())
      throw Error("final gather", "near source " + std::to_string(i) + " names patch " +
                                      std::to_string(near.patch[i]) + " of " +
                                      std::to_string(patch_indirect.size()));
  const float eps = tracer ? 10.0f * tracer->epsilon() : 0.0f;
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
    std::vector<ShadowRay> rays;
    std::vector<glm::vec3> value, e;
    std::vector<std::uint32_t> who;
    std::vector<std::uint8_t> blocked;
    rays.reserve(kBatch);
    value.reserve(kBatch);
    who.reserve(kBatch);
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t bi = 0; bi < static_cast<std::int64_t>(batches); ++bi) {
      const std::size_t lo = static_cast<std::size_t>(bi) * kBatch, hi = std::min(n, lo + kBatch);
      e.assign(hi - lo, glm::vec3(0.0f));
      if (tracer) {
        for (const LightReach& light : reach) {
          rays.clear();
          value.clear();
          who.clear();
          for (std::size_t i = lo; i < hi; ++i) {
            // Lifted once here and once more by the light's own offset, as
            // irradiance_at() lifts the point it is given.
            const glm::vec3 at = near.position[i] + eps * near.normal[i];
            const UnshadowedLight u = light.at(at, near.normal[i], eps);
            if (!u.reaches) continue;
            rays.push_back(u.ray);
            value.push_back(u.value);
            who.push_back(static_cast<std::uint32_t>(i - lo));
          }
          blocked.resize(rays.size());
          tracer->occluded(rays.data(), rays.size(), blocked.data());
          for (std::size_t k = 0; k < rays.size(); ++k)
            if (!blocked[k]) e[who[k]] += value[k];
        }
        for (const AreaLight& light : area)
          for (std::size_t i = lo; i < hi; ++i)
            e[i - lo] += area_light_irradiance(*tracer, near.position[i] + eps * near.normal[i],
                                               near.normal[i], light, 4, i);
      }
      for (std::size_t i = lo; i < hi; ++i)
        out[i] = near.albedo[i] * e[i - lo] + patch_indirect[near.patch[i]];
    }
  }
}

void FinalGather::validate(const std::string& what) const {
  if (first.empty() || first.front() != 0 || first.back() != source.size() ||
      source.size() != weight.size())
    throw Error(what, "row offsets do not match the " + std::to_string(source.size()) + " entries");
  if (cluster_of_patch.size() != patches || cluster_share.size() != patches)
    throw Error(what, "one cluster and share per patch expected");
  for (std::size_t p = 0; p < patches; ++p)
    if (cluster_of_patch[p] >= clusters || !(cluster_share[p] >= 0.0f && cluster_share[p] <= 1.0f))
      throw Error(what, "patch " + std::to_string(p) + "'s cluster or share is out of range");
  if (near.normal.size() != near.size() || near.albedo.size() != near.size() ||
      near.patch.size() != near.size())
    throw Error(what, "near sources need a position, normal, albedo and patch each");
  if (near.size() > 0 && samples == 0)
    throw Error(what, "near sources without the bake's sample count");
  for (std::size_t k = 0; k < near.size(); ++k) {
    const glm::vec3 v[3] = {near.position[k], near.normal[k], near.albedo[k]};
    for (const glm::vec3& x : v)
      if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
        throw Error(what, "near source " + std::to_string(k) + " is not finite");
    if (near.patch[k] >= patches)
      throw Error(what, "near source " + std::to_string(k) + " names patch " +
                            std::to_string(near.patch[k]) + " of " + std::to_string(patches));
  }
  for (std::size_t i = 0; i + 1 < first.size(); ++i) {
    if (first[i + 1] < first[i])
      throw Error(what, "row offsets decrease at point " + std::to_string(i));
    double total = 0.0;
    for (std::uint64_t k = first[i]; k < first[i + 1]; ++k) {
      if (source[k] >= patches + clusters + samples + near.size())
        throw Error(what, "point " + std::to_string(i) + " gathers from source " +
                              std::to_string(source[k]) + " of " +
                              std::to_string(patches + clusters + samples + near.size()));
      if (!(weight[k] >= 0.0f && weight[k] <= 1.0f))
        throw Error(what, "point " + std::to_string(i) + " has a weight outside [0, 1]");
      total += weight[k];
    }
    if (total > 1.0 + 1e-4)
      throw Error(what, "point " + std::to_string(i) + "'s weights sum to " +
                            std::to_string(total) + " > 1");
  }
}

std::size_t FinalGatherSettings::sample_cap() const {
  if (sample_kept <= 0 || rays <= 0) return 0;
  return static_cast<std::size_t>(
      std::ceil(static_cast<double>(sample_kept) * static_cast<double>(rays) / 256.0));
}

std::vector<glm::vec3> gather_points_of_vertices(const std::vector<glm::vec3>& positions,
                                                 const std::vector<glm::uvec3>& triangles) {
  std::vector<glm::vec3> out = positions;
  std::vector<bool> moved(positions.size(), false);
  for (const glm::uvec3& t : triangles) {
    const glm::vec3 c = (positions[t.x] + positions[t.y] + positions[t.z]) / 3.0f;
    for (int k = 0; k < 3; ++k) {
      if (t[k] >= positions.size() || moved[t[k]]) continue;
      out[t[k]] = positions[t[k]] + 0.05f * (c - positions[t[k]]);
      moved[t[k]] = true;
    }
  }
  return out;
}

void light_vertices(const RayTracer& tracer, const std::vector<Light>& lights,
                    const std::vector<AreaLight>& area, const std::vector<glm::vec3>& gathered,
                    LitMesh& mesh) {
  const std::size_t n = mesh.positions.size();
  if (gathered.size() != n) throw Error("final gather", "one gathered value per vertex expected");
  const Scene& scene = tracer.scene();
  const std::vector<std::uint32_t> triangle = vertex_source_triangles(mesh);
  const std::vector<glm::vec3> at = gather_points_of_vertices(mesh.positions, mesh.triangles);
  mesh.radiosity.resize(n);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t vi = 0; vi < static_cast<std::int64_t>(n); ++vi) {
    const auto v = static_cast<std::size_t>(vi);
    const glm::vec3 direct =
        irradiance_at(tracer, at[v] + 10.0f * tracer.epsilon() * mesh.normals[v], mesh.normals[v],
                      lights, area, 4, v);
    mesh.radiosity[v] =
        scene.emission_at(triangle[v], mesh.positions[v]) +
        scene.flat_albedo_at(triangle[v], mesh.positions[v]) * (direct + gathered[v]);
  }
}

namespace {

// Clusters: the patches of one block of `block` x `block` x `block` voxels
// whose normals share a dominant axis direction (a floor and the wall
// standing on it stay apart) and whose positions along that axis lie in one
// quarter-voxel layer (a floor and the lit top of a slab standing on it stay
// apart too: a point under the slab sees the floor, not the slab's top),
// numbered in order of first appearance.
void make_clusters(const std::vector<Patch>& patches, const VoxelGrid& grid, int block,
                   FinalGather& g) {
  std::map<std::tuple<int, int, int, int, int>, std::uint32_t> index;
  g.cluster_of_patch.resize(patches.size());
  g.cluster_share.resize(patches.size());
  std::vector<double> area;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const glm::ivec3 c = grid.cell_of(patches[p].position) / block;
    const glm::vec3 a = glm::abs(patches[p].normal);
    const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    // Emitters are clusters of their own: a lamp's light differs from the
    // surface it hangs on (and a point light next to a lamp makes its patches
    // the brightest of the scene).
    const bool emits = glm::dot(patches[p].emission, glm::vec3(1.0f)) > 0.0f;
    const int direction = 2 * axis + (patches[p].normal[axis] < 0.0f ? 1 : 0) + (emits ? 6 : 0);
    const int layer = static_cast<int>(std::floor(
        (patches[p].position[axis] - grid.bounds().lo[axis]) / (0.25f * grid.cell_size())));
    const auto [it, added] = index.try_emplace({c.x, c.y, c.z, direction, layer},
                                               static_cast<std::uint32_t>(index.size()));
    if (added) area.push_back(0.0);
    g.cluster_of_patch[p] = it->second;
    area[it->second] += patches[p].area;
  }
  g.clusters = index.size();
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const double a = area[g.cluster_of_patch[p]];
    g.cluster_share[p] = a > 0.0 ? static_cast<float>(patches[p].area / a) : 0.0f;
  }
}

// A near source's identity: the sample whose surface the rays landed on,
// the triangle they landed on (so that its mean landing point lies on that
// triangle and its normal is that triangle's) and the cell of the
// near-source lattice they landed in.
struct NearKey {
  std::int32_t sample, x, y, z;
  std::uint32_t triangle;
  bool operator==(const NearKey&) const = default;
};

struct NearKeyHash {
  std::size_t operator()(const NearKey& k) const {
    std::uint64_t h = static_cast<std::uint32_t>(k.sample) * 0x9E3779B97F4A7C15ull;
    for (const std::int32_t v : {k.x, k.y, k.z, static_cast<std::int32_t>(k.triangle)})
      h = (h ^ static_cast<std::uint32_t>(v)) * 0xBF58476D1CE4E5B9ull;
    return static_cast<std::size_t>(h ^ (h >> 31));
  }
};

// The near sources one chunk of points found, numbered in order of first
// landing: sums of the landing points and their albedo, and the side's normal.
struct ChunkNearSources {
  std::vector<NearKey> keys;
  std::vector<glm::dvec3> position_sum, albedo_sum;
  std::vector<glm::vec3> normal;
  std::vector<std::uint32_t> count;
};

// Chunk rows name a near source by its chunk-local number with this bit set
// until the chunks are merged.
constexpr std::uint32_t kChunkNearSource = 0x80000000u;

}  // namespace

FinalGather build_final_gather(const RayTracer& tracer, const SurfacePatchLookup& lookup,
                               const std::vector<Patch>& patch_list, const VoxelGrid& grid,
                               const std::vector<glm::vec3>& positions,
                               const std::vector<glm::vec3>& normals,
                               const FinalGatherSettings& settings, Progress* progress) {
  if (positions.size() != normals.size())
    throw Error("final gather", "positions and normals differ in count");
  if (settings.rays < 1 || settings.kept < 1 || settings.cluster_voxels < 1)
    throw Error("final gather", "rays, kept patches and cluster size per point must be at least 1");
  if (settings.sample_kept < 0 ||
      !(settings.sample_coverage >= 0.0 && settings.sample_coverage <= 1.0))
    throw Error("final gather", "kept samples must be >= 0 and their coverage in [0, 1]");
  if (!(settings.near_cells >= 0.0f && settings.near_cells <= 16.0f) ||
      settings.near_resolution < 1 || settings.near_resolution > 1024)
    throw Error("final gather",
                "the near distance must be in [0, 16] voxels and the near sources' resolution "
                "in [1, 1024] per voxel");
  const std::size_t patch_count = patch_list.size();
  FinalGather g;
  g.patches = patch_count;
  g.rays = settings.rays;
  make_clusters(patch_list, grid, settings.cluster_voxels, g);
  const std::size_t n = positions.size();
  const auto rays = static_cast<std::size_t>(settings.rays);
  const auto kept = static_cast<std::size_t>(settings.kept);
  const std::size_t sample_kept = settings.sample_cap();
  const bool sample_sources = sample_kept > 0 && settings.sample_coverage > 0.0;
  const bool near_sources = settings.near_cells > 0.0f;
  if (sample_sources || near_sources) g.samples = lookup.sample_count();
  const float near_distance = settings.near_cells * grid.cell_size();
  const float near_cell = grid.cell_size() / static_cast<float>(settings.near_resolution);
  const std::size_t sample_base = patch_count + g.clusters;
  const float eps = settings.offset_epsilons * tracer.epsilon();
  const Scene& scene = tracer.scene();
  // Each point turns the lattice by its own angle.
  const CosineLattice lattice(rays);

  // Rows are built in chunks of points, each chunk's rows kept in its own
  // buffer and joined in point order at the end.
  constexpr std::size_t kChunk = 256;
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<std::vector<std::uint32_t>> chunk_patch(chunks);
  std::vector<std::vector<float>> chunk_weight(chunks);
  std::vector<std::vector<std::uint32_t>> chunk_count(chunks);
  std::vector<ChunkNearSources> chunk_near(chunks);
  if (progress) progress->begin_stage("final gather", std::max<std::size_t>(1, chunks));
  std::size_t escaped = 0, backs = 0, unrepresented = 0, landed_rays = 0, near_rays = 0;
#pragma omp parallel reduction(+ : escaped, backs, unrepresented, landed_rays, near_rays)
  {
    std::unordered_map<NearKey, std::uint32_t, NearKeyHash> near_index;
    std::vector<std::uint32_t> near_hits, near_touched;
    std::vector<std::uint32_t> hits(patch_count, 0), cluster_hits(g.clusters, 0);
    std::vector<std::uint32_t> touched, cluster_touched;
    std::vector<std::uint32_t> sample_hits(sample_sources ? g.samples : 0, 0), samples_touched;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t ci = 0; ci < static_cast<std::int64_t>(chunks); ++ci) {
      if (progress && progress->should_stop()) continue;
      const auto c = static_cast<std::size_t>(ci);
      ChunkNearSources& cn = chunk_near[c];
      near_index.clear();
      near_hits.clear();
      for (std::size_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i) {
        const glm::vec3 nrm = normals[i];
        touched.clear();
        samples_touched.clear();
        near_touched.clear();
        if (glm::dot(nrm, nrm) > 0.5f) {
          Rng rng(settings.seed, 0xF1A1u ^ (static_cast<std::uint64_t>(i) << 16));
          const CosineLattice::Frame frame(nrm, 2.0f * std::numbers::pi_v<float> * rng.uniform());
          const glm::vec3 lifted = positions[i] + eps * nrm;
          for (std::size_t k = 0; k < rays; ++k) {
            const glm::vec3 dir = lattice.direction(k, frame);
            glm::vec3 origin = lifted;
            const Hit h = intersect_leaving_surface(tracer, origin, dir, eps);
            if (!h.hit) {
              ++escaped;
              continue;
            }
            const bool back = glm::dot(dir, h.geometric_normal) > 0.0f;
            if (back && !scene.two_sided(h.triangle)) {
              ++backs;
              continue;
            }
            const glm::vec3 x = origin + h.t * dir;
            const std::int32_t s = lookup.sample_at(h.triangle, back, x);
            if (s < 0) {
              ++unrepresented;
              continue;
            }
            const std::int32_t p = lookup.patch_of(static_cast<std::uint32_t>(s));
            ++landed_rays;
            if (near_sources && glm::distance(x, lifted) < near_distance) {
              const glm::ivec3 cell(glm::floor(x / near_cell));
              const auto [it, added] =
                  near_index.try_emplace(NearKey{s, cell.x, cell.y, cell.z, h.triangle},
                                         static_cast<std::uint32_t>(cn.keys.size()));
              const std::uint32_t id = it->second;
              if (added) {
                cn.keys.push_back(it->first);
                cn.position_sum.emplace_back(0.0);
                cn.albedo_sum.emplace_back(0.0);
                cn.normal.push_back(back ? -h.geometric_normal : h.geometric_normal);
                cn.count.push_back(0);
                near_hits.push_back(0);
              }
              cn.position_sum[id] += glm::dvec3(x);
              cn.albedo_sum[id] += glm::dvec3(scene.albedo_at(h.triangle, x));
              ++cn.count[id];
              if (near_hits[id]++ == 0) near_touched.push_back(id);
              ++near_rays;
              continue;
            }
            if (hits[static_cast<std::size_t>(p)]++ == 0)
              touched.push_back(static_cast<std::uint32_t>(p));
            if (sample_sources && sample_hits[static_cast<std::size_t>(s)]++ == 0)
              samples_touched.push_back(static_cast<std::uint32_t>(s));
          }
        }
        const double per_ray = 1.0 / static_cast<double>(rays);
        std::size_t entries = 0;
        if (sample_sources) {
          // The strongest samples first, ties by index; their rays leave
          // their patch's count.
          std::sort(samples_touched.begin(), samples_touched.end(),
                    [&](std::uint32_t a, std::uint32_t b) {
                      return sample_hits[a] != sample_hits[b] ? sample_hits[a] > sample_hits[b]
                                                              : a < b;
                    });
          std::size_t landed = 0, covered = 0;
          for (std::uint32_t p : touched) landed += hits[p];
          for (std::uint32_t s : samples_touched) {
            if (entries >= sample_kept ||
                static_cast<double>(covered) >=
                    settings.sample_coverage * static_cast<double>(landed))
              break;
            covered += sample_hits[s];
            hits[static_cast<std::size_t>(lookup.patch_of(s))] -= sample_hits[s];
            chunk_patch[c].push_back(static_cast<std::uint32_t>(sample_base + s));
            chunk_weight[c].push_back(static_cast<float>(per_ray * sample_hits[s]));
            ++entries;
          }
          for (std::uint32_t s : samples_touched) sample_hits[s] = 0;
          // Patches whose every ray went to their kept samples drop out.
          touched.erase(std::remove_if(touched.begin(), touched.end(),
                                       [&](std::uint32_t p) { return hits[p] == 0; }),
                        touched.end());
        }
        // The strongest `kept` exactly, ties by patch index
        // (deterministic); the rest's hits go to their clusters.
        std::sort(touched.begin(), touched.end(), [&](std::uint32_t a, std::uint32_t b) {
          return hits[a] != hits[b] ? hits[a] > hits[b] : a < b;
        });
        std::size_t keep = 0, landed = 0, covered = 0;
        for (std::uint32_t p : touched) landed += hits[p];
        while (keep < std::min(kept, touched.size()) &&
               static_cast<double>(covered) < settings.coverage * static_cast<double>(landed))
          covered += hits[touched[keep++]];
        entries += keep;
        for (std::size_t k = 0; k < keep; ++k) {
          chunk_patch[c].push_back(touched[k]);
          chunk_weight[c].push_back(static_cast<float>(per_ray * hits[touched[k]]));
        }
        cluster_touched.clear();
        for (std::size_t k = keep; k < touched.size(); ++k) {
          const std::uint32_t cl = g.cluster_of_patch[touched[k]];
          if (cluster_hits[cl] == 0) cluster_touched.push_back(cl);
          cluster_hits[cl] += hits[touched[k]];
        }
        std::sort(cluster_touched.begin(), cluster_touched.end());
        for (std::uint32_t cl : cluster_touched) {
          chunk_patch[c].push_back(static_cast<std::uint32_t>(patch_count + cl));
          chunk_weight[c].push_back(static_cast<float>(per_ray * cluster_hits[cl]));
          cluster_hits[cl] = 0;
          ++entries;
        }
        // The near sources, in order of first landing within the chunk.
        std::sort(near_touched.begin(), near_touched.end());
        for (std::uint32_t id : near_touched) {
          chunk_patch[c].push_back(kChunkNearSource | id);
          chunk_weight[c].push_back(static_cast<float>(per_ray * near_hits[id]));
          near_hits[id] = 0;
          ++entries;
        }
        chunk_count[c].push_back(static_cast<std::uint32_t>(entries));
        for (std::uint32_t p : touched) hits[p] = 0;
      }
      if (progress) progress->advance();
    }
  }
  if (progress) {
    progress->check();
    progress->end_stage();
  }
  g.rays_landed = landed_rays;
  g.rays_escaped = escaped;
  g.rays_back = backs;
  g.rays_unrepresented = unrepresented;
  g.rays_near = near_rays;
  // Near sources found by several chunks become one, numbered in chunk order
  // (the same whatever the thread count).
  std::vector<std::vector<std::uint32_t>> near_number(chunks);
  std::vector<std::uint32_t> count, near_sample;
  {
    std::unordered_map<NearKey, std::uint32_t, NearKeyHash> index;
    std::vector<glm::dvec3> position_sum, albedo_sum;
    for (std::size_t c = 0; c < chunks; ++c) {
      const ChunkNearSources& cn = chunk_near[c];
      for (std::size_t l = 0; l < cn.keys.size(); ++l) {
        const auto [it, added] =
            index.try_emplace(cn.keys[l], static_cast<std::uint32_t>(count.size()));
        if (added) {
          position_sum.emplace_back(0.0);
          albedo_sum.emplace_back(0.0);
          count.push_back(0);
          near_sample.push_back(static_cast<std::uint32_t>(cn.keys[l].sample));
          g.near.normal.push_back(cn.normal[l]);
          g.near.patch.push_back(static_cast<std::uint32_t>(
              lookup.patch_of(static_cast<std::uint32_t>(cn.keys[l].sample))));
        }
        position_sum[it->second] += cn.position_sum[l];
        albedo_sum[it->second] += cn.albedo_sum[l];
        count[it->second] += cn.count[l];
        near_number[c].push_back(it->second);
      }
    }
    for (std::size_t k = 0; k < count.size(); ++k) {
      g.near.position.push_back(glm::vec3(position_sum[k] / static_cast<double>(count[k])));
      g.near.albedo.push_back(glm::vec3(albedo_sum[k] / static_cast<double>(count[k])));
    }
  }
  // Near sources that fewer than `near_min_rays` rays landed in (over all
  // points) go back to the sample, patch or cluster the point reads for
  // that surface: each costs a shadow ray every frame for a ray or two of
  // light, noise at one point's 1 / rays.
  constexpr std::uint32_t kDissolved = 0xFFFFFFFFu;
  std::vector<std::uint32_t> near_id(count.size());
  {
    NearSources kept_near;
    for (std::size_t k = 0; k < count.size(); ++k) {
      if (count[k] < static_cast<std::uint32_t>(std::max(1, settings.near_min_rays))) {
        near_id[k] = kDissolved;
        g.rays_near -= count[k];
        continue;
      }
      near_id[k] = static_cast<std::uint32_t>(kept_near.size());
      kept_near.position.push_back(g.near.position[k]);
      kept_near.normal.push_back(g.near.normal[k]);
      kept_near.albedo.push_back(g.near.albedo[k]);
      kept_near.patch.push_back(g.near.patch[k]);
    }
    g.near = std::move(kept_near);
  }
  const std::size_t near_base = patch_count + g.clusters + g.samples;
  const double per_ray = 1.0 / static_cast<double>(rays);
  const auto hits_of = [rays](float w) {
    return static_cast<std::uint32_t>(
        std::lround(static_cast<double>(w) * static_cast<double>(rays)));
  };
  for (std::size_t c = 0; c < chunks; ++c) {
    std::vector<std::uint32_t> src_out;
    std::vector<float> weight_out;
    src_out.reserve(chunk_patch[c].size());
    weight_out.reserve(chunk_weight[c].size());
    std::size_t at = 0;
    for (std::uint32_t& row_count : chunk_count[c]) {
      const std::size_t row_begin = src_out.size();
      std::vector<std::pair<std::uint32_t, std::uint32_t>> folded;  // (sample, hits)
      for (std::size_t k = at; k < at + row_count; ++k) {
        std::uint32_t src = chunk_patch[c][k];
        if (src & kChunkNearSource) {
          const std::uint32_t global = near_number[c][src & ~kChunkNearSource];
          if (near_id[global] == kDissolved) {
            folded.emplace_back(near_sample[global], hits_of(chunk_weight[c][k]));
            continue;
          }
          src = static_cast<std::uint32_t>(near_base + near_id[global]);
        }
        src_out.push_back(src);
        weight_out.push_back(chunk_weight[c][k]);
      }
      // A folded ray joins the row's entry for its sample, else its patch,
      // else its patch's cluster, else a new entry for its patch.
      for (const auto& [sample, hits] : folded) {
        const auto p = static_cast<std::uint32_t>(lookup.patch_of(sample));
        const std::uint32_t targets[3] = {
            static_cast<std::uint32_t>(sample_base + sample), p,
            static_cast<std::uint32_t>(patch_count) + g.cluster_of_patch[p]};
        std::size_t found = src_out.size();
        for (const std::uint32_t t : targets) {
          for (std::size_t e = row_begin; e < src_out.size() && found == src_out.size(); ++e)
            if (src_out[e] == t) found = e;
          if (found != src_out.size()) break;
        }
        if (found == src_out.size()) {
          src_out.push_back(p);
          weight_out.push_back(0.0f);
        }
        weight_out[found] = static_cast<float>(per_ray * (hits_of(weight_out[found]) + hits));
      }
      at += row_count;
      row_count = static_cast<std::uint32_t>(src_out.size() - row_begin);
    }
    chunk_patch[c] = std::move(src_out);
    chunk_weight[c] = std::move(weight_out);
  }
  g.first.reserve(n + 1);
  g.first.push_back(0);
  for (std::size_t c = 0; c < chunks; ++c) {
    for (std::uint32_t k : chunk_count[c]) g.first.push_back(g.first.back() + k);
    g.source.insert(g.source.end(), chunk_patch[c].begin(), chunk_patch[c].end());
    g.weight.insert(g.weight.end(), chunk_weight[c].begin(), chunk_weight[c].end());
  }
  g.compact_rows();
  return g;
}

}  // namespace bounce
