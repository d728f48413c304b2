#include "runtime/final_gather.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>
#include <unordered_map>

#include "base/error.h"
#include "base/random.h"
#include "raytrace/cosine_lattice.h"
#include "runtime/direct_light.h"

namespace bounce {

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
// landing: sums of the landing points and their albedo, the first landing
// point and its side's normal.
struct ChunkNearSources {
  std::vector<NearKey> keys;
  std::vector<glm::dvec3> position_sum, albedo_sum;
  std::vector<glm::vec3> first, normal;
  std::vector<std::uint32_t> count;
};

// Chunk rows name a near source by its chunk-local number with this bit set
// until the chunks are merged.
constexpr std::uint32_t kChunkNearSource = 0x80000000u;

// The seen weights (FinalGather::seen_first) from the rays read through
// patch and cluster entries: each patch's samples weighed by the rays that
// landed on them, each patch's share of its cluster by the rays folded into
// it. A patch or cluster no such ray landed on keeps its area weights.
void weigh_by_seen_rays(const SurfacePatchLookup& lookup, const std::vector<std::uint64_t>& seen,
                        const std::vector<std::uint64_t>& cluster_rays, FinalGather& g) {
  std::vector<std::uint64_t> patch_total(g.patches, 0);
  std::vector<std::uint32_t> patch_entries(g.patches, 0);
  for (std::size_t s = 0; s < seen.size(); ++s)
    if (seen[s] > 0) {
      const auto p = static_cast<std::size_t>(lookup.patch_of(static_cast<std::uint32_t>(s)));
      patch_total[p] += seen[s];
      ++patch_entries[p];
    }
  g.seen_first.assign(g.patches + 1, 0);
  for (std::size_t p = 0; p < g.patches; ++p)
    g.seen_first[p + 1] = g.seen_first[p] + patch_entries[p];
  g.seen_sample.resize(g.seen_first.back());
  g.seen_weight.resize(g.seen_first.back());
  std::vector<std::uint32_t> at(g.seen_first.begin(), g.seen_first.end() - 1);
  for (std::size_t s = 0; s < seen.size(); ++s)
    if (seen[s] > 0) {
      const auto p = static_cast<std::size_t>(lookup.patch_of(static_cast<std::uint32_t>(s)));
      g.seen_sample[at[p]] = static_cast<std::uint32_t>(s);
      g.seen_weight[at[p]++] =
          static_cast<float>(static_cast<double>(seen[s]) / static_cast<double>(patch_total[p]));
    }
  std::vector<std::uint64_t> cluster_total(g.clusters, 0);
  for (std::size_t p = 0; p < g.patches; ++p)
    cluster_total[g.cluster_of_patch[p]] += cluster_rays[p];
  for (std::size_t p = 0; p < g.patches; ++p)
    if (const std::uint64_t t = cluster_total[g.cluster_of_patch[p]]; t > 0)
      g.cluster_share[p] =
          static_cast<float>(static_cast<double>(cluster_rays[p]) / static_cast<double>(t));
}

// A spot's cell as the far rays found it: how many landed in it, and the
// first of them (in point and ray order, so that the spot is the same
// whatever the thread count): where it landed and the side it landed on.
struct SpotCell {
  std::uint64_t rays = 0, first = 0;
  glm::vec3 position{0.0f}, normal{0.0f};
};
using SpotCells = std::unordered_map<NearKey, SpotCell, NearKeyHash>;

void add_to_spot_cell(SpotCells& cells, const NearKey& key, const SpotCell& cell) {
  const auto [it, added] = cells.try_emplace(key, cell);
  if (added) return;
  it->second.rays += cell.rays;
  if (cell.first < it->second.first) {
    it->second.first = cell.first;
    it->second.position = cell.position;
    it->second.normal = cell.normal;
  }
}

// Each sample's `spots` cells with the most far rays (ties by first ray)
// become its spots, weighted by their rays: FinalGather::spot_first, and
// the spots appended to the near sources, lit with the sample's albedo.
void make_spots(const SurfacePatchLookup& lookup, const SpotCells& cells, int spots,
                FinalGather& g) {
  struct Candidate {
    std::uint32_t sample;
    SpotCell cell;
  };
  std::vector<Candidate> all;
  all.reserve(cells.size());
  for (const auto& [key, cell] : cells)
    all.push_back({static_cast<std::uint32_t>(key.sample), cell});
  std::sort(all.begin(), all.end(), [](const Candidate& a, const Candidate& b) {
    if (a.sample != b.sample) return a.sample < b.sample;
    if (a.cell.rays != b.cell.rays) return a.cell.rays > b.cell.rays;
    return a.cell.first < b.cell.first;
  });
  const SampleSet& samples = lookup.samples();
  g.spot_first.assign(g.samples + 1, 0);
  std::vector<std::uint32_t> count(g.samples, 0);
  std::size_t at = 0;
  while (at < all.size()) {
    const std::uint32_t s = all[at].sample;
    std::size_t end = at;
    while (end < all.size() && all[end].sample == s) ++end;
    const std::size_t kept = std::min(end - at, static_cast<std::size_t>(spots));
    std::uint64_t total = 0;
    for (std::size_t k = at; k < at + kept; ++k) total += all[k].cell.rays;
    for (std::size_t k = at; k < at + kept; ++k) {
      g.spot_weight.push_back(
          static_cast<float>(static_cast<double>(all[k].cell.rays) / static_cast<double>(total)));
      g.near.position.push_back(all[k].cell.position);
      g.near.normal.push_back(all[k].cell.normal);
      g.near.albedo.push_back(samples.samples[s].albedo);
      g.near.patch.push_back(static_cast<std::uint32_t>(lookup.patch_of(s)));
    }
    count[s] = static_cast<std::uint32_t>(kept);
    at = end;
  }
  for (std::size_t s = 0; s < g.samples; ++s) g.spot_first[s + 1] = g.spot_first[s] + count[s];
  g.near.spot_count = g.spot_first.back();
}

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
  if (settings.spots < 0 || settings.spots > 64 || settings.spot_resolution < 1 ||
      settings.spot_resolution > 1024)
    throw Error("final gather",
                "spots per sample must be in [0, 64] and their resolution in [1, 1024] per voxel");
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
  const bool spot_sources = (sample_sources || near_sources) && settings.spots > 0;
  const float spot_cell = grid.cell_size() / static_cast<float>(settings.spot_resolution);
  SpotCells spot_cells;
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
  std::size_t escaped = 0, backs = 0, unrepresented = 0, landed_rays = 0, near_rays = 0,
              points_enclosed = 0;
  // Over all points: the rays read through a patch or cluster entry that
  // landed on each sample, and those folded into a cluster per patch (they
  // weigh the sources' light, see FinalGather::seen_first).
  std::vector<std::uint64_t> seen_rays(sample_sources ? g.samples : 0, 0),
      cluster_rays(sample_sources ? patch_count : 0, 0);
#pragma omp parallel reduction(+ : escaped, backs, unrepresented, landed_rays, near_rays, \
                                    points_enclosed)
  {
    struct TracedRay {
      Hit hit;
      glm::vec3 origin;
    };
    std::vector<TracedRay> traced;
    std::vector<std::uint64_t> seen_local(seen_rays.size(), 0),
        cluster_local(cluster_rays.size(), 0);
    std::unordered_map<NearKey, std::uint32_t, NearKeyHash> near_index;
    std::vector<std::uint32_t> near_hits, near_touched;
    std::vector<std::uint32_t> hits(patch_count, 0), cluster_hits(g.clusters, 0);
    std::vector<std::uint32_t> touched, cluster_touched;
    std::vector<std::uint32_t> sample_hits(sample_sources ? g.samples : 0, 0), samples_touched;
    SpotCells spot_local;
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
          traced.clear();
          std::size_t point_backs = 0;
          for (std::size_t k = 0; k < rays; ++k) {
            const glm::vec3 dir = lattice.direction(k, frame);
            glm::vec3 origin = lifted;
            const Hit h = intersect_leaving_surface(tracer, origin, dir, eps);
            traced.push_back({h, origin});
            if (h.hit && glm::dot(dir, h.geometric_normal) > 0.0f && !scene.two_sided(h.triangle))
              ++point_backs;
          }
          // A point more than half of whose rays meet the back of a one-sided
          // face is shut inside the geometry (a mesh's face under a block
          // standing on it): no light reaches it, and the surface its other
          // rays land on, under the block, must not pull the near sources
          // and spots of the points outside there.
          const bool enclosed = 2 * point_backs > rays;
          if (enclosed) ++points_enclosed;
          for (std::size_t k = 0; k < rays && !enclosed; ++k) {
            const glm::vec3 dir = lattice.direction(k, frame);
            const Hit& h = traced[k].hit;
            const glm::vec3& origin = traced[k].origin;
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
                cn.first.push_back(x);
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
            if (spot_sources) {
              const glm::ivec3 cell(glm::floor(x / spot_cell));
              add_to_spot_cell(spot_local, NearKey{s, cell.x, cell.y, cell.z, h.triangle},
                               SpotCell{1, static_cast<std::uint64_t>(i) * rays + k, x,
                                        back ? -h.geometric_normal : h.geometric_normal});
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
          bool keeping = true;
          for (std::uint32_t s : samples_touched) {
            keeping = keeping && entries < sample_kept &&
                      static_cast<double>(covered) <
                          settings.sample_coverage * static_cast<double>(landed);
            if (!keeping) {
              seen_local[s] += sample_hits[s];
              continue;
            }
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
          if (sample_sources) cluster_local[touched[k]] += hits[touched[k]];
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
#pragma omp critical(final_gather_seen_rays)
    {
      for (std::size_t s = 0; s < seen_local.size(); ++s) seen_rays[s] += seen_local[s];
      for (std::size_t p = 0; p < cluster_local.size(); ++p) cluster_rays[p] += cluster_local[p];
      for (const auto& [key, cell] : spot_local) add_to_spot_cell(spot_cells, key, cell);
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
  g.points_enclosed = points_enclosed;
  // Near sources found by several chunks become one, numbered in chunk order
  // (the same whatever the thread count).
  std::vector<std::vector<std::uint32_t>> near_number(chunks);
  std::vector<std::uint32_t> count, near_sample;
  {
    std::unordered_map<NearKey, std::uint32_t, NearKeyHash> index;
    std::vector<glm::dvec3> position_sum, albedo_sum;
    std::vector<glm::vec3> first;
    for (std::size_t c = 0; c < chunks; ++c) {
      const ChunkNearSources& cn = chunk_near[c];
      for (std::size_t l = 0; l < cn.keys.size(); ++l) {
        const auto [it, added] =
            index.try_emplace(cn.keys[l], static_cast<std::uint32_t>(count.size()));
        if (added) {
          position_sum.emplace_back(0.0);
          albedo_sum.emplace_back(0.0);
          first.push_back(cn.first[l]);
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
    g.near.position.resize(count.size());
    // Each is lit at the mean of its landing points unless the way there
    // from its first landing point, a hair above the surface, is blocked:
    // then the mean lies under something standing on its triangle.
#pragma omp parallel for schedule(static, 1024)
    for (std::int64_t ki = 0; ki < static_cast<std::int64_t>(count.size()); ++ki) {
      const auto k = static_cast<std::size_t>(ki);
      const glm::vec3 mean(position_sum[k] / static_cast<double>(count[k]));
      const glm::vec3 lift = eps * g.near.normal[k];
      const glm::vec3 to_mean = mean - first[k];
      const bool blocked = glm::dot(to_mean, to_mean) > 0.0f &&
                           tracer.occluded(first[k] + lift, to_mean, 0.0f, 1.0f);
      g.near.position[k] = blocked ? first[k] : mean;
    }
    for (std::size_t k = 0; k < count.size(); ++k)
      g.near.albedo.push_back(glm::vec3(albedo_sum[k] / static_cast<double>(count[k])));
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
    std::vector<std::pair<std::uint32_t, std::uint32_t>> folded;  // (sample, hits) of a row
    for (std::uint32_t& row_count : chunk_count[c]) {
      const std::size_t row_begin = src_out.size();
      folded.clear();
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
        if (src_out[found] < sample_base && !seen_rays.empty()) {
          seen_rays[sample] += hits;
          if (src_out[found] >= patch_count) cluster_rays[p] += hits;
        }
        weight_out[found] = static_cast<float>(per_ray * (hits_of(weight_out[found]) + hits));
      }
      at += row_count;
      row_count = static_cast<std::uint32_t>(src_out.size() - row_begin);
    }
    chunk_patch[c] = std::move(src_out);
    chunk_weight[c] = std::move(weight_out);
  }
  // The spots go after the near sources the rows read.
  if (spot_sources) make_spots(lookup, spot_cells, settings.spots, g);
  g.first.reserve(n + 1);
  g.first.push_back(0);
  for (std::size_t c = 0; c < chunks; ++c) {
    for (std::uint32_t k : chunk_count[c]) g.first.push_back(g.first.back() + k);
    g.source.insert(g.source.end(), chunk_patch[c].begin(), chunk_patch[c].end());
    g.weight.insert(g.weight.end(), chunk_weight[c].begin(), chunk_weight[c].end());
  }
  if (!seen_rays.empty()) weigh_by_seen_rays(lookup, seen_rays, cluster_rays, g);
  g.compact_rows();
  return g;
}

}  // namespace bounce
