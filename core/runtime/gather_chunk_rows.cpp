#include "runtime/gather_chunk_rows.h"

#include <algorithm>
#include <numbers>
#include <unordered_map>

#include "base/random.h"
#include "raytrace/cosine_lattice.h"
#include "runtime/final_gather_settings.h"

namespace bounce {

RayTally& RayTally::operator+=(const RayTally& o) {
  landed += o.landed;
  escaped += o.escaped;
  back += o.back;
  unrepresented += o.unrepresented;
  near += o.near;
  enclosed += o.enclosed;
  return *this;
}

GatherPlan plan_of(const FinalGatherSettings& settings, const VoxelGrid& grid,
                   const RayTracer& tracer, const FinalGather& g) {
  GatherPlan p;
  p.rays = static_cast<std::size_t>(settings.rays);
  p.kept = static_cast<std::size_t>(settings.kept);
  p.sample_kept = settings.sample_cap();
  p.coverage = settings.coverage;
  p.sample_coverage = settings.sample_coverage;
  p.sample_sources = p.sample_kept > 0 && settings.sample_coverage > 0.0;
  p.near_sources = settings.near > 0.0f;
  p.spot_sources = (p.sample_sources || p.near_sources) && settings.spots > 0;
  p.near_distance = settings.near * grid.cell_size();
  p.near_cell = grid.cell_size() / static_cast<float>(settings.near_resolution);
  p.spot_cell = grid.cell_size() / static_cast<float>(settings.spot_resolution);
  p.offset = settings.offset_epsilons * tracer.epsilon();
  p.seed = settings.seed;
  p.patches = g.patches;
  p.sample_base = g.patches + g.clusters;
  return p;
}

namespace {

// What every point of one build reads.
struct GatherInputs {
  const RayTracer& tracer;
  const SurfacePatchLookup& lookup;
  const GatherPlan& plan;
  const FinalGather& g;
  const CosineLattice& lattice;
};

struct TracedRay {
  Hit hit;
  glm::vec3 origin;
};

// One thread's working memory, kept from point to point: the ray counts per
// patch, cluster, sample and chunk-local near source of the current point
// (each with the list of those it touched, to clear them), and this
// thread's share of the build's totals.
struct PointScratch {
  PointScratch(const GatherPlan& plan, const FinalGather& g)
      : hits(plan.patches, 0),
        cluster_hits(g.clusters, 0),
        sample_hits(plan.sample_sources ? g.samples : 0, 0),
        seen(plan.sample_sources ? g.samples : 0, 0),
        cluster_rays(plan.sample_sources ? plan.patches : 0, 0) {}
  std::vector<TracedRay> traced;
  std::unordered_map<SurfaceCellKey, std::uint32_t, SurfaceCellKeyHash> near_index;
  std::vector<std::uint32_t> near_hits, near_touched;
  std::vector<std::uint32_t> hits, cluster_hits, touched, cluster_touched;
  std::vector<std::uint32_t> sample_hits, samples_touched;
  std::vector<std::uint64_t> seen, cluster_rays;
  SpotCells spots;
  RayTally tally;
};

// Traces a point's rays into w.traced. Returns whether the point is shut
// inside the geometry: more than half of its rays meet the back of a
// one-sided face (a mesh's face under a block standing on it). No light
// reaches it, and the surface its other rays land on, under the block, must
// not pull the near sources and spots of the points outside there.
bool trace_point_rays(const GatherInputs& in, const CosineLattice::Frame& frame,
                      const glm::vec3& lifted, PointScratch& w) {
  const Scene& scene = in.tracer.scene();
  w.traced.clear();
  std::size_t backs = 0;
  for (std::size_t k = 0; k < in.plan.rays; ++k) {
    const glm::vec3 dir = in.lattice.direction(k, frame);
    glm::vec3 origin = lifted;
    const Hit h = intersect_leaving_surface(in.tracer, origin, dir, in.plan.offset);
    w.traced.push_back({h, origin});
    if (h.hit && glm::dot(dir, h.geometric_normal) > 0.0f && !scene.two_sided(h.triangle)) ++backs;
  }
  return 2 * backs > in.plan.rays;
}

// A ray landing at `x` within the near distance: counted in the chunk's near
// source for its cell (added on its first ray) and in the point's.
void land_near(const Scene& scene, const SurfaceCellKey& key, const glm::vec3& x,
               const glm::vec3& side, PointScratch& w, ChunkNearSources& cn) {
  const auto [it, added] =
      w.near_index.try_emplace(key, static_cast<std::uint32_t>(cn.keys.size()));
  const std::uint32_t id = it->second;
  if (added) {
    cn.keys.push_back(key);
    cn.position_sum.emplace_back(0.0);
    cn.first.push_back(x);
    cn.albedo_sum.emplace_back(0.0);
    cn.normal.push_back(side);
    cn.count.push_back(0);
    w.near_hits.push_back(0);
  }
  cn.position_sum[id] += glm::dvec3(x);
  cn.albedo_sum[id] += glm::dvec3(scene.albedo_at(key.triangle, x));
  ++cn.count[id];
  if (w.near_hits[id]++ == 0) w.near_touched.push_back(id);
  ++w.tally.near;
}

// Where each traced ray of point i went: nowhere (escaped, the back of a
// one-sided face, surface no sample stands for), a near source, or a sample
// and its patch (and the spot cell it landed in).
void land_rays(const GatherInputs& in, std::size_t i, const CosineLattice::Frame& frame,
               const glm::vec3& lifted, PointScratch& w, ChunkNearSources& cn) {
  const Scene& scene = in.tracer.scene();
  const GatherPlan& plan = in.plan;
  for (std::size_t k = 0; k < plan.rays; ++k) {
    const glm::vec3 dir = in.lattice.direction(k, frame);
    const Hit& h = w.traced[k].hit;
    if (!h.hit) {
      ++w.tally.escaped;
      continue;
    }
    const bool back = glm::dot(dir, h.geometric_normal) > 0.0f;
    if (back && !scene.two_sided(h.triangle)) {
      ++w.tally.back;
      continue;
    }
    const glm::vec3 x = w.traced[k].origin + h.t * dir;
    const std::int32_t s = in.lookup.sample_at(h.triangle, back, x);
    if (s < 0) {
      ++w.tally.unrepresented;
      continue;
    }
    const auto p = static_cast<std::size_t>(in.lookup.patch_of(static_cast<std::uint32_t>(s)));
    ++w.tally.landed;
    const glm::vec3 side = back ? -h.geometric_normal : h.geometric_normal;
    if (plan.near_sources && glm::distance(x, lifted) < plan.near_distance) {
      const glm::ivec3 cell(glm::floor(x / plan.near_cell));
      land_near(scene, {s, cell.x, cell.y, cell.z, h.triangle}, x, side, w, cn);
      continue;
    }
    if (plan.spot_sources) {
      const glm::ivec3 cell(glm::floor(x / plan.spot_cell));
      w.spots.add({s, cell.x, cell.y, cell.z, h.triangle},
                  SpotCell{1, static_cast<std::uint64_t>(i) * plan.rays + k, x, side});
    }
    if (w.hits[p]++ == 0) w.touched.push_back(static_cast<std::uint32_t>(p));
    if (plan.sample_sources && w.sample_hits[static_cast<std::size_t>(s)]++ == 0)
      w.samples_touched.push_back(static_cast<std::uint32_t>(s));
  }
}

// The point's sample entries: the strongest samples first (ties by index),
// until they hold the sample coverage of its landed rays or reach the cap;
// their rays leave their patch's count. The others' rays stay with their
// patch and count as seen through it. Returns the entries added.
std::size_t add_sample_entries(const GatherInputs& in, PointScratch& w, ChunkRows& rows) {
  const GatherPlan& plan = in.plan;
  const double per_ray = 1.0 / static_cast<double>(plan.rays);
  std::vector<std::uint32_t>& sh = w.sample_hits;
  std::sort(
      w.samples_touched.begin(), w.samples_touched.end(),
      [&](std::uint32_t a, std::uint32_t b) { return sh[a] != sh[b] ? sh[a] > sh[b] : a < b; });
  std::size_t landed = 0, covered = 0, entries = 0;
  for (std::uint32_t p : w.touched) landed += w.hits[p];
  bool keeping = true;
  for (std::uint32_t s : w.samples_touched) {
    keeping = keeping && entries < plan.sample_kept &&
              static_cast<double>(covered) < plan.sample_coverage * static_cast<double>(landed);
    if (!keeping) {
      w.seen[s] += sh[s];
      continue;
    }
    covered += sh[s];
    w.hits[static_cast<std::size_t>(in.lookup.patch_of(s))] -= sh[s];
    rows.source.push_back(static_cast<std::uint32_t>(plan.sample_base + s));
    rows.weight.push_back(static_cast<float>(per_ray * sh[s]));
    ++entries;
  }
  for (std::uint32_t s : w.samples_touched) sh[s] = 0;
  // Patches whose every ray went to their kept samples drop out.
  w.touched.erase(std::remove_if(w.touched.begin(), w.touched.end(),
                                 [&](std::uint32_t p) { return w.hits[p] == 0; }),
                  w.touched.end());
  return entries;
}

// The point's patch entries: the strongest `kept` exactly, until they hold
// the coverage of its landed rays, ties by patch index (deterministic). The
// rest's rays go to their clusters, one entry each in cluster order.
// Returns the entries added.
std::size_t add_patch_and_cluster_entries(const GatherInputs& in, PointScratch& w,
                                          ChunkRows& rows) {
  const GatherPlan& plan = in.plan;
  const double per_ray = 1.0 / static_cast<double>(plan.rays);
  std::vector<std::uint32_t>& hits = w.hits;
  std::sort(w.touched.begin(), w.touched.end(), [&](std::uint32_t a, std::uint32_t b) {
    return hits[a] != hits[b] ? hits[a] > hits[b] : a < b;
  });
  std::size_t keep = 0, landed = 0, covered = 0;
  for (std::uint32_t p : w.touched) landed += hits[p];
  while (keep < std::min(plan.kept, w.touched.size()) &&
         static_cast<double>(covered) < plan.coverage * static_cast<double>(landed))
    covered += hits[w.touched[keep++]];
  for (std::size_t k = 0; k < keep; ++k) {
    rows.source.push_back(w.touched[k]);
    rows.weight.push_back(static_cast<float>(per_ray * hits[w.touched[k]]));
  }
  w.cluster_touched.clear();
  for (std::size_t k = keep; k < w.touched.size(); ++k) {
    const std::uint32_t p = w.touched[k];
    if (plan.sample_sources) w.cluster_rays[p] += hits[p];
    const std::uint32_t cl = in.g.cluster_of_patch[p];
    if (w.cluster_hits[cl] == 0) w.cluster_touched.push_back(cl);
    w.cluster_hits[cl] += hits[p];
  }
  std::sort(w.cluster_touched.begin(), w.cluster_touched.end());
  for (std::uint32_t cl : w.cluster_touched) {
    rows.source.push_back(static_cast<std::uint32_t>(plan.patches + cl));
    rows.weight.push_back(static_cast<float>(per_ray * w.cluster_hits[cl]));
    w.cluster_hits[cl] = 0;
  }
  return keep + w.cluster_touched.size();
}

// The point's near-source entries, in order of first landing within the
// chunk, named by chunk-local number until the chunks are merged.
std::size_t add_near_entries(const GatherInputs& in, PointScratch& w, ChunkRows& rows) {
  const double per_ray = 1.0 / static_cast<double>(in.plan.rays);
  std::sort(w.near_touched.begin(), w.near_touched.end());
  for (std::uint32_t id : w.near_touched) {
    rows.source.push_back(kChunkNearSource | id);
    rows.weight.push_back(static_cast<float>(per_ray * w.near_hits[id]));
    w.near_hits[id] = 0;
  }
  return w.near_touched.size();
}

// Point i's row: its rays traced (each point turns the lattice by its own
// angle) and landed, then its sample, patch, cluster and near entries.
void gather_point(const GatherInputs& in, std::size_t i, const glm::vec3& position,
                  const glm::vec3& normal, PointScratch& w, ChunkRows& rows) {
  w.touched.clear();
  w.samples_touched.clear();
  w.near_touched.clear();
  if (glm::dot(normal, normal) > 0.5f) {
    Rng rng(in.plan.seed, 0xF1A1u ^ (static_cast<std::uint64_t>(i) << 16));
    const CosineLattice::Frame frame(normal, 2.0f * std::numbers::pi_v<float> * rng.uniform());
    const glm::vec3 lifted = position + in.plan.offset * normal;
    if (trace_point_rays(in, frame, lifted, w))
      ++w.tally.enclosed;
    else
      land_rays(in, i, frame, lifted, w, rows.near);
  }
  std::size_t entries = 0;
  if (in.plan.sample_sources) entries += add_sample_entries(in, w, rows);
  entries += add_patch_and_cluster_entries(in, w, rows);
  entries += add_near_entries(in, w, rows);
  rows.count.push_back(static_cast<std::uint32_t>(entries));
  for (std::uint32_t p : w.touched) w.hits[p] = 0;
}

// A thread's totals into the build's (under a lock; all are sums or, for
// spot cells, order-free merges).
void add_thread_totals(const PointScratch& w, TracedRows& out) {
  out.tally += w.tally;
  for (std::size_t s = 0; s < w.seen.size(); ++s) out.seen_rays[s] += w.seen[s];
  for (std::size_t p = 0; p < w.cluster_rays.size(); ++p) out.cluster_rays[p] += w.cluster_rays[p];
  out.spot_cells.merge(w.spots);
}

}  // namespace

TracedRows trace_rows(const RayTracer& tracer, const SurfacePatchLookup& lookup,
                      const std::vector<glm::vec3>& positions,
                      const std::vector<glm::vec3>& normals, const GatherPlan& plan,
                      const FinalGather& g, Progress* progress) {
  constexpr std::size_t kChunk = 256;
  const std::size_t n = positions.size();
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  TracedRows out;
  out.chunks.resize(chunks);
  out.seen_rays.assign(plan.sample_sources ? g.samples : 0, 0);
  out.cluster_rays.assign(plan.sample_sources ? plan.patches : 0, 0);
  const CosineLattice lattice(plan.rays);
  const GatherInputs in{tracer, lookup, plan, g, lattice};
  if (progress) progress->begin_stage("final gather", std::max<std::size_t>(1, chunks));
#pragma omp parallel
  {
    PointScratch w(plan, g);
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t ci = 0; ci < static_cast<std::int64_t>(chunks); ++ci) {
      if (progress && progress->should_stop()) continue;
      const auto c = static_cast<std::size_t>(ci);
      w.near_index.clear();
      w.near_hits.clear();
      for (std::size_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i)
        gather_point(in, i, positions[i], normals[i], w, out.chunks[c]);
      if (progress) progress->advance();
    }
#pragma omp critical(final_gather_thread_totals)
    add_thread_totals(w, out);
  }
  if (progress) {
    progress->check();
    progress->end_stage();
  }
  return out;
}

}  // namespace bounce
