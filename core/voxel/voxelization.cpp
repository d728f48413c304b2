#include "voxel/voxelization.h"

#include <algorithm>
#include <cmath>

#include <omp.h>

namespace bounce {

namespace {

using Polygon = std::vector<glm::dvec3>;

// Keeps the part of `poly` with sign * (p[axis] - value) >= 0 (Sutherland-Hodgman).
Polygon clip(const Polygon& poly, int axis, double value, double sign) {
  Polygon out;
  const std::size_t n = poly.size();
  for (std::size_t k = 0; k < n; ++k) {
    const glm::dvec3& p = poly[k];
    const glm::dvec3& q = poly[(k + 1) % n];
    const double dp = sign * (p[axis] - value), dq = sign * (q[axis] - value);
    if (dp >= 0.0) out.push_back(p);
    if ((dp >= 0.0) != (dq >= 0.0)) {
      const double t = dp / (dp - dq);
      glm::dvec3 x = p + t * (q - p);
      x[axis] = value;  // exactly on the plane, so neighbours agree
      out.push_back(x);
    }
  }
  return out;
}

double polygon_area(const Polygon& poly) {
  if (poly.size() < 3) return 0.0;
  glm::dvec3 sum(0.0);
  for (std::size_t k = 1; k + 1 < poly.size(); ++k)
    sum += glm::cross(poly[k] - poly[0], poly[k + 1] - poly[0]);
  return 0.5 * glm::length(sum);
}

struct Piece {
  std::uint64_t cell;
  std::uint32_t triangle;
  float area;
  std::vector<glm::vec3> polygon;
};

// Splits `poly` into the cells it crosses, one axis at a time.
void split(const VoxelGrid& grid, const Polygon& poly, int axis, glm::ivec3 coord,
           std::uint32_t triangle, std::vector<Piece>& out) {
  double lo = poly[0][axis], hi = poly[0][axis];
  for (const auto& p : poly) {
    lo = std::min(lo, p[axis]);
    hi = std::max(hi, p[axis]);
  }
  const double origin = grid.bounds().lo[axis], cell = grid.cell_size();
  const int last = grid.dims()[axis] - 1;
  const int i0 = std::clamp(static_cast<int>(std::floor((lo - origin) / cell)), 0, last);
  const int i1 = std::clamp(static_cast<int>(std::floor((hi - origin) / cell)), 0, last);
  for (int i = i0; i <= i1; ++i) {
    Polygon piece = poly;
    // A polygon flat along this axis lies in exactly one cell (half-open
    // cells); clipping it with closed half-spaces would count it twice when
    // it lies on a cell plane.
    if (i0 != i1) {
      if (i > i0) piece = clip(piece, axis, origin + i * cell, +1.0);
      if (i < i1 && piece.size() >= 3) piece = clip(piece, axis, origin + (i + 1) * cell, -1.0);
      if (piece.size() < 3) continue;
    }
    coord[axis] = i;
    if (axis < 2) {
      split(grid, piece, axis + 1, coord, triangle, out);
    } else {
      const double area = polygon_area(piece);
      if (area > 0.0) {
        std::vector<glm::vec3> polygon(piece.begin(), piece.end());
        out.push_back(
            {grid.linear_index(coord), triangle, static_cast<float>(area), std::move(polygon)});
      }
    }
  }
}

}  // namespace

std::int64_t Voxelization::find(const glm::ivec3& coord) const {
  const glm::ivec3 d = grid.dims();
  if (coord.x < 0 || coord.y < 0 || coord.z < 0 || coord.x >= d.x || coord.y >= d.y ||
      coord.z >= d.z)
    return -1;
  const auto it = voxel_of_cell.find(grid.linear_index(coord));
  return it == voxel_of_cell.end() ? -1 : static_cast<std::int64_t>(it->second);
}

float clipped_triangle_area(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                            const Bounds& box) {
  Polygon poly{glm::dvec3(a), glm::dvec3(b), glm::dvec3(c)};
  for (int axis = 0; axis < 3 && poly.size() >= 3; ++axis) {
    poly = clip(poly, axis, box.lo[axis], +1.0);
    if (poly.size() >= 3) poly = clip(poly, axis, box.hi[axis], -1.0);
  }
  return static_cast<float>(polygon_area(poly));
}

Voxelization voxelize(const Scene& scene, const VoxelGrid& grid, Progress* progress) {
  const std::size_t n = scene.triangle_count();
  if (progress) progress->begin_stage("voxelize", n);
  const int threads = omp_get_max_threads();
  std::vector<std::vector<Piece>> per_thread(static_cast<std::size_t>(threads));
  const std::int64_t count = static_cast<std::int64_t>(n);
  constexpr std::int64_t kChunk = 1024;
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t start = 0; start < count; start += kChunk) {
    if (progress && progress->should_stop()) continue;
    auto& out = per_thread[static_cast<std::size_t>(omp_get_thread_num())];
    const std::int64_t end = std::min(count, start + kChunk);
    for (std::int64_t t = start; t < end; ++t) {
      const auto tri = static_cast<std::size_t>(t);
      Polygon poly{glm::dvec3(scene.vertex(tri, 0)), glm::dvec3(scene.vertex(tri, 1)),
                   glm::dvec3(scene.vertex(tri, 2))};
      split(grid, poly, 0, glm::ivec3(0), static_cast<std::uint32_t>(tri), out);
    }
    if (progress) progress->advance(static_cast<std::size_t>(end - start));
  }
  if (progress) progress->check();

  std::vector<Piece> pieces;
  for (auto& v : per_thread)
    for (auto& p : v) pieces.push_back(std::move(p));
  std::sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) {
    return a.cell != b.cell ? a.cell < b.cell : a.triangle < b.triangle;
  });

  Voxelization vox{grid, {}, {}, {}, {}};
  vox.parts.reserve(pieces.size());
  for (const Piece& p : pieces) {
    if (vox.voxels.empty() || vox.voxels.back().cell != p.cell) {
      OccupiedVoxel v;
      v.cell = p.cell;
      v.coord = grid.coord_of(p.cell);
      v.first_part = static_cast<std::uint32_t>(vox.parts.size());
      vox.voxel_of_cell.emplace(p.cell, static_cast<std::uint32_t>(vox.voxels.size()));
      vox.voxels.push_back(v);
    }
    vox.parts.push_back({p.triangle, p.area, static_cast<std::uint32_t>(vox.part_vertices.size()),
                         static_cast<std::uint32_t>(p.polygon.size())});
    vox.part_vertices.insert(vox.part_vertices.end(), p.polygon.begin(), p.polygon.end());
    vox.voxels.back().part_count++;
    vox.voxels.back().area += p.area;
  }
  if (progress) progress->end_stage();
  return vox;
}

}  // namespace bounce
