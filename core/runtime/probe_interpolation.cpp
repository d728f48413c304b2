#include "runtime/probe_interpolation.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/error.h"

namespace bounce {

namespace {

// A probe's position is its cell's centre up to float rounding; a fraction
// of a cell closer to a whole cell than this is that rounding, not an
// offset, so a point given at a probe's position takes that probe alone.
constexpr float kSnap = 1e-4f;
// The last resort: cells within this many of the point's own (5 x 5 x 5),
// at most this many rays, nearest probe first.
constexpr int kReach = 2;
constexpr int kReachRays = 16;

std::uint64_t linear(const TransferGrid& g, const glm::ivec3& c) {
  return (static_cast<std::uint64_t>(c.z) * static_cast<std::uint64_t>(g.dims.y) +
          static_cast<std::uint64_t>(c.y)) *
             static_cast<std::uint64_t>(g.dims.x) +
         static_cast<std::uint64_t>(c.x);
}

bool inside(const TransferGrid& g, const glm::ivec3& c) {
  return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < g.dims.x && c.y < g.dims.y && c.z < g.dims.z;
}

void normalise(ProbeBlend& b) {
  float total = 0.0f;
  for (std::size_t i = 0; i < b.count; ++i) total += b.weight[i];
  if (total <= 0.0f) {
    b.count = 0;
    return;
  }
  for (std::size_t i = 0; i < b.count; ++i) b.weight[i] /= total;
}

}  // namespace

ProbeInterpolator::ProbeInterpolator(const std::vector<glm::vec3>& positions,
                                     const TransferGrid& grid, const RayTracer& tracer,
                                     const std::vector<ProbeLattice>& volumes)
    : positions_(positions), tracer_(tracer) {
  std::vector<bool> in_volume(positions.size(), false);
  for (const ProbeLattice& v : volumes) {
    if (v.first > positions.size() || v.count > positions.size() - v.first)
      throw Error("light probes", "a volume's probes " + std::to_string(v.first) + " to " +
                                      std::to_string(v.first + v.count) + " of " +
                                      std::to_string(positions.size()));
    Lattice& lattice = volumes_.emplace_back(Lattice{v.grid, {}});
    for (std::size_t p = v.first; p < v.first + v.count; ++p) {
      if (in_volume[p])
        throw Error("light probes", "probe " + std::to_string(p) + " is in two volumes");
      in_volume[p] = true;
      add_probe(lattice, static_cast<std::uint32_t>(p));
    }
    check_distinct(lattice);
  }
  surfaces_.grid = grid;
  for (std::size_t p = 0; p < positions.size(); ++p)
    if (!in_volume[p]) add_probe(surfaces_, static_cast<std::uint32_t>(p));
  check_distinct(surfaces_);
}

void ProbeInterpolator::add_probe(Lattice& lattice, std::uint32_t probe) const {
  const TransferGrid& g = lattice.grid;
  const glm::vec3 u = (positions_[probe] - g.origin) / g.cell_size - 0.5f;
  const glm::vec3 whole = glm::round(u);
  const glm::ivec3 c(whole);
  if (glm::any(glm::greaterThan(glm::abs(u - whole), glm::vec3(1e-3f))) || !inside(g, c))
    throw Error("light probes",
                "probe " + std::to_string(probe) + " is not at the centre of a cell of its grid");
  lattice.cells.emplace_back(linear(g, c), probe);
}

void ProbeInterpolator::check_distinct(Lattice& lattice) {
  auto& cells = lattice.cells;
  std::sort(cells.begin(), cells.end());
  for (std::size_t i = 1; i < cells.size(); ++i)
    if (cells[i].first == cells[i - 1].first)
      throw Error("light probes", "probes " + std::to_string(cells[i - 1].second) + " and " +
                                      std::to_string(cells[i].second) + " share a cell");
}

std::int64_t ProbeInterpolator::Lattice::probe_in(const glm::ivec3& c) const {
  if (!inside(grid, c)) return -1;
  const std::uint64_t key = linear(grid, c);
  const auto it =
      std::lower_bound(cells.begin(), cells.end(), std::make_pair(key, std::uint32_t{0}));
  return it != cells.end() && it->first == key ? static_cast<std::int64_t>(it->second) : -1;
}

float ProbeInterpolator::Lattice::share_at(const glm::vec3& point) const {
  const glm::vec3 u = (point - grid.origin) / grid.cell_size;
  float depth = 0.5f;  // in cells from the edge; the outer probes stand at 0.5
  for (int a = 0; a < 3; ++a)
    depth = std::min({depth, u[a], static_cast<float>(grid.dims[a]) - u[a]});
  return depth > 0.0f ? 2.0f * depth : 0.0f;  // also 0 for NaN
}

// A surface anywhere on the segment is a wall between: the probe's light
// there is not the point's. Both ends stand off surfaces (a probe by half a
// voxel), so the segment's ends need no margin beyond the tracer's epsilon.
bool ProbeInterpolator::sees(const glm::vec3& point, std::uint32_t probe) const {
  const glm::vec3 d = positions_[probe] - point;
  const float length = glm::length(d);
  const float eps = tracer_.epsilon();
  if (length <= 2.0f * eps) return true;
  return !tracer_.occluded(point, d / length, eps, length - eps);
}

void ProbeInterpolator::consider(const glm::vec3& point, std::uint32_t probe, float weight,
                                 ProbeVisibility visibility, ProbeBlend& out) const {
  if (weight <= 0.0f) return;  // no share in the blend: no ray either
  if (visibility == ProbeVisibility::kTested) {
    ++out.rays;
    if (!sees(point, probe)) return;
  }
  out.probe[out.count] = probe;
  out.weight[out.count] = weight;
  ++out.count;
}

void ProbeInterpolator::trilinear(const Lattice& lattice, const glm::vec3& point,
                                  ProbeVisibility visibility, ProbeBlend& out) const {
  const glm::vec3 u = (point - lattice.grid.origin) / lattice.grid.cell_size - 0.5f;
  const glm::vec3 base = glm::floor(u);
  glm::vec3 f = u - base;
  for (int a = 0; a < 3; ++a) {
    if (f[a] < kSnap) f[a] = 0.0f;
    if (f[a] > 1.0f - kSnap) f[a] = 1.0f;
  }
  for (int corner = 0; corner < 8; ++corner) {
    const glm::ivec3 step(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    float w = 1.0f;
    for (int a = 0; a < 3; ++a) w *= step[a] ? f[a] : 1.0f - f[a];
    const std::int64_t p = lattice.probe_in(glm::ivec3(base) + step);
    if (p >= 0) consider(point, static_cast<std::uint32_t>(p), w, visibility, out);
  }
  normalise(out);
  if (out.count > 0) out.stage = ProbeBlend::Stage::kTrilinear;
}

// The probes of the 27 cells around the point's own are at most 1.5 cells
// from it along each axis: a tent of half-width 2 cells gives each of them
// a share that falls off with distance and never reaches 0.
void ProbeInterpolator::neighbourhood(const glm::vec3& point, ProbeVisibility visibility,
                                      ProbeBlend& out) const {
  const glm::ivec3 centre = surfaces_.grid.cell_of(point);
  for (int z = -1; z <= 1; ++z)
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x) {
        const std::int64_t p = surfaces_.probe_in(centre + glm::ivec3(x, y, z));
        if (p < 0) continue;
        const glm::vec3 d =
            glm::abs(positions_[static_cast<std::size_t>(p)] - point) / surfaces_.grid.cell_size;
        float w = 1.0f;
        for (int a = 0; a < 3; ++a) w *= std::max(0.0f, 1.0f - 0.5f * d[a]);
        consider(point, static_cast<std::uint32_t>(p), w, visibility, out);
      }
  normalise(out);
  if (out.count > 0) out.stage = ProbeBlend::Stage::kNeighbourhood;
}

void ProbeInterpolator::nearest_in_reach(const glm::vec3& point, ProbeVisibility visibility,
                                         ProbeBlend& out) const {
  const glm::ivec3 centre = surfaces_.grid.cell_of(point);
  std::vector<std::pair<float, std::uint32_t>> near;
  for (int z = -kReach; z <= kReach; ++z)
    for (int y = -kReach; y <= kReach; ++y)
      for (int x = -kReach; x <= kReach; ++x) {
        const std::int64_t p = surfaces_.probe_in(centre + glm::ivec3(x, y, z));
        if (p < 0) continue;
        const auto probe = static_cast<std::uint32_t>(p);
        const glm::vec3 d = positions_[probe] - point;
        near.emplace_back(glm::dot(d, d), probe);
      }
  std::sort(near.begin(), near.end());
  const std::size_t tries = std::min<std::size_t>(near.size(), kReachRays);
  for (std::size_t i = 0; i < tries; ++i) {
    if (visibility == ProbeVisibility::kTested) {
      ++out.rays;
      if (!sees(point, near[i].second)) continue;
    }
    out.probe[0] = near[i].second;
    out.weight[0] = 1.0f;
    out.count = 1;
    out.stage = ProbeBlend::Stage::kNearest;
    return;
  }
}

ProbeBlend ProbeInterpolator::blend(const glm::vec3& point, ProbeVisibility visibility) const {
  ProbeBlend out;  // a lattice that finds no probe leaves it empty but for its rays
  for (const Lattice& volume : volumes_) {
    const float share = volume.share_at(point);
    if (share <= 0.0f) continue;
    trilinear(volume, point, visibility, out);
    if (out.count == 0) continue;
    if (share < 1.0f) fade_to_surfaces(point, visibility, share, out);
    return out;
  }
  surfaces_blend(point, visibility, out);
  return out;
}

void ProbeInterpolator::surfaces_blend(const glm::vec3& point, ProbeVisibility visibility,
                                       ProbeBlend& out) const {
  trilinear(surfaces_, point, visibility, out);
  if (out.count == 0) neighbourhood(point, visibility, out);
  if (out.count == 0) nearest_in_reach(point, visibility, out);
}

// `out`, a volume's blend, keeps `share` of the weight; the probes next to
// the surfaces get the rest, when any of them sees the point.
void ProbeInterpolator::fade_to_surfaces(const glm::vec3& point, ProbeVisibility visibility,
                                         float share, ProbeBlend& out) const {
  ProbeBlend rest;
  surfaces_blend(point, visibility, rest);
  out.rays += rest.rays;
  if (rest.count == 0) return;
  for (std::size_t i = 0; i < out.count; ++i) out.weight[i] *= share;
  for (std::size_t i = 0; i < rest.count; ++i) {
    out.probe[out.count] = rest.probe[i];
    out.weight[out.count] = (1.0f - share) * rest.weight[i];
    ++out.count;
  }
}

ProbeBlend ProbeInterpolator::sh_at(const glm::vec3& point, const std::vector<glm::vec3>& sh,
                                    std::array<glm::vec3, kShCoefficients>& out,
                                    ProbeVisibility visibility) const {
  if (sh.size() != positions_.size() * kShCoefficients)
    throw Error("light probes", std::to_string(sh.size()) + " SH coefficients for " +
                                    std::to_string(positions_.size()) + " probes");
  const ProbeBlend b = blend(point, visibility);
  out.fill(glm::vec3(0.0f));
  for (std::size_t i = 0; i < b.count; ++i)
    for (std::size_t j = 0; j < kShCoefficients; ++j)
      out[j] += b.weight[i] * sh[b.probe[i] * kShCoefficients + j];
  return b;
}

}  // namespace bounce
