#include "runtime/light_probe_placement.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>

#include "base/error.h"

namespace bounce {

namespace {

// Empty cells sharing a face with an occupied one, in increasing linear
// index, without duplicates.
std::vector<std::uint64_t> candidate_cells(const Voxelization& voxels) {
  const glm::ivec3 dims = voxels.grid.dims();
  std::vector<std::uint64_t> cells;
  cells.reserve(6 * voxels.voxels.size());
  for (const OccupiedVoxel& v : voxels.voxels)
    for (int axis = 0; axis < 3; ++axis)
      for (const int step : {-1, 1}) {
        glm::ivec3 c = v.coord;
        c[axis] += step;
        if (c[axis] < 0 || c[axis] >= dims[axis] || voxels.find(c) >= 0) continue;
        cells.push_back(voxels.grid.linear_index(c));
      }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  return cells;
}

std::vector<glm::vec3> sphere_directions(int n) {
  std::vector<glm::vec3> d(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 2.0 * std::numbers::pi * i / std::numbers::phi;
    d[static_cast<std::size_t>(i)] =
        glm::vec3(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
                  static_cast<float>(z));
  }
  return d;
}

enum class Verdict : std::uint8_t { kKept, kEnclosed, kSeesNothing };

Verdict judge(const RayTracer& tracer, const glm::vec3& centre,
              const std::vector<glm::vec3>& directions) {
  const Scene& scene = tracer.scene();
  std::size_t backs = 0, fronts = 0;
  for (const glm::vec3& dir : directions) {
    const Hit h = tracer.intersect(centre, dir);
    if (!h.hit) continue;
    if (glm::dot(dir, h.geometric_normal) > 0.0f && !scene.two_sided(h.triangle))
      ++backs;
    else
      ++fronts;
  }
  if (2 * backs > directions.size()) return Verdict::kEnclosed;
  return fronts == 0 ? Verdict::kSeesNothing : Verdict::kKept;
}

std::string box_text(const glm::vec3& lo, const glm::vec3& hi) {
  char text[160];
  std::snprintf(text, sizeof text, "(%g, %g, %g) to (%g, %g, %g)", lo.x, lo.y, lo.z, hi.x, hi.y,
                hi.z);
  return text;
}

// Every volume meets the scene's bounds and its lattice fits the limit;
// then the candidates together must too.
void check_request(const ProbePlacementRequest& request, const Bounds& scene,
                   std::size_t surface_candidates) {
  double total = static_cast<double>(surface_candidates);
  for (std::size_t i = 0; i < request.volumes.size(); ++i) {
    const ProbeVolume& v = request.volumes[i];
    const std::string which = "volume " + std::to_string(i + 1) + " " + box_text(v.lo, v.hi);
    const std::string where = std::string("setting '") + request.volumes_setting + "'";
    if (glm::any(glm::lessThan(v.hi, scene.lo)) || glm::any(glm::greaterThan(v.lo, scene.hi)))
      throw Error(where,
                  which + " lies outside the scene's bounds " + box_text(scene.lo, scene.hi));
    const double points = volume_point_count(v);
    if (points > static_cast<double>(request.max_probes)) {
      char text[200];
      std::snprintf(text, sizeof text,
                    " at spacing %g makes %.4g probes, more than the %zu setting '%s' allows: "
                    "widen its spacing or shrink it",
                    static_cast<double>(v.spacing), points, request.max_probes,
                    request.max_setting);
      throw Error(where, which + text);
    }
    total += points;
  }
  if (total > static_cast<double>(request.max_probes))
    throw Error(std::string("setting '") + request.max_setting + "'",
                "the placement has " + std::to_string(static_cast<std::size_t>(total)) +
                    " candidates (" + std::to_string(surface_candidates) +
                    " empty cells next to surfaces, the rest the probe volumes' lattices), "
                    "more than the " +
                    std::to_string(request.max_probes) +
                    " allowed: raise it, bake on a coarser grid or widen the volumes' spacing");
}

std::vector<glm::vec3> cell_centres(const VoxelGrid& grid,
                                    const std::vector<std::uint64_t>& cells) {
  std::vector<glm::vec3> out;
  out.reserve(cells.size());
  for (const std::uint64_t c : cells) {
    const Bounds box = grid.cell_bounds(grid.coord_of(c));
    out.push_back(0.5f * (box.lo + box.hi));
  }
  return out;
}

void add_lattice_points(const TransferGrid& g, std::vector<glm::vec3>& out) {
  for (int z = 0; z < g.dims.z; ++z)
    for (int y = 0; y < g.dims.y; ++y)
      for (int x = 0; x < g.dims.x; ++x)
        out.push_back(g.origin + g.cell_size * (glm::vec3(x, y, z) + 0.5f));
}

std::vector<Verdict> judge_all(const RayTracer& tracer, const std::vector<glm::vec3>& points) {
  const std::vector<glm::vec3> directions = sphere_directions(kProbeTestRays);
  std::vector<Verdict> verdict(points.size());
#pragma omp parallel for schedule(dynamic, 64)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(points.size()); ++i)
    verdict[static_cast<std::size_t>(i)] =
        judge(tracer, points[static_cast<std::size_t>(i)], directions);
  return verdict;
}

// Keeps the points [begin, end) the test accepts; returns how many it kept
// and counts the rejected by reason.
std::size_t keep(const std::vector<glm::vec3>& points, const std::vector<Verdict>& verdict,
                 std::size_t begin, std::size_t end, std::size_t& enclosed,
                 std::size_t& sees_nothing, std::vector<glm::vec3>& out) {
  std::size_t kept = 0;
  for (std::size_t k = begin; k < end; ++k) {
    if (verdict[k] == Verdict::kEnclosed) {
      ++enclosed;
    } else if (verdict[k] == Verdict::kSeesNothing) {
      ++sees_nothing;
    } else {
      out.push_back(points[k]);
      ++kept;
    }
  }
  return kept;
}

}  // namespace

std::vector<ProbeLattice> ProbePlacement::lattices() const {
  std::vector<ProbeLattice> out;
  std::size_t first = position.size();
  for (const VolumePlacement& v : volumes) first -= v.placed;
  for (const VolumePlacement& v : volumes) {
    out.push_back({v.lattice, first, v.placed});
    first += v.placed;
  }
  return out;
}

ProbePlacement place_light_probes(const RayTracer& tracer, const Voxelization& voxels,
                                  const ProbePlacementRequest& request, Progress* progress) {
  ProbePlacement placement;
  std::vector<std::uint64_t> cells;
  if (request.surfaces) cells = candidate_cells(voxels);
  const bool skip_surfaces = request.surfaces_optional && cells.size() > request.max_probes;
  if (skip_surfaces) {
    placement.surfaces_skipped = "the grid has " + std::to_string(cells.size()) +
                                 " empty cells next to surfaces, more than the " +
                                 std::to_string(request.max_probes) + " " + request.max_setting +
                                 " allows";
    placement.candidates = cells.size();
    cells.clear();
  }
  check_request(request, tracer.scene().bounds(), cells.size());
  placement.surfaces = request.surfaces && !skip_surfaces;
  if (placement.surfaces) placement.candidates = cells.size();

  std::vector<glm::vec3> points = cell_centres(voxels.grid, cells);
  for (const ProbeVolume& v : request.volumes) {
    VolumePlacement& vp = placement.volumes.emplace_back();
    vp.volume = v;
    vp.lattice = volume_lattice(v);
    // The points the loop below adds, so the ranges of `verdict` line up
    // (check_request has bounded their count).
    const glm::ivec3 d = vp.lattice.dims;
    vp.candidates = static_cast<std::size_t>(d.x) * static_cast<std::size_t>(d.y) *
                    static_cast<std::size_t>(d.z);
    add_lattice_points(vp.lattice, points);
  }
  if (progress) progress->begin_stage("light probe placement", points.size());
  const std::vector<Verdict> verdict = judge_all(tracer, points);
  keep(points, verdict, 0, cells.size(), placement.rejected_enclosed,
       placement.rejected_sees_nothing, placement.position);
  std::size_t begin = cells.size();
  for (VolumePlacement& vp : placement.volumes) {
    vp.placed = keep(points, verdict, begin, begin + vp.candidates, vp.rejected_enclosed,
                     vp.rejected_sees_nothing, placement.position);
    begin += vp.candidates;
  }
  if (progress) {
    progress->advance(points.size());
    progress->end_stage();
  }
  return placement;
}

}  // namespace bounce
