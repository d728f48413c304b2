#pragma once
// Which triangles overlap which cells, and the exact area of each triangle
// clipped to each cell. Only occupied cells are stored ("empty voxels get
// nothing"), in increasing linear-index order.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "base/progress.h"
#include "scene/scene.h"
#include "voxel/voxel_grid.h"

namespace bounce {

struct TrianglePart {
  std::uint32_t triangle;
  float area;  // area of the triangle clipped to the voxel
  // Its clipped polygon: Voxelization::part_vertices[first_vertex ..
  // first_vertex + vertex_count), used for exact near-field form factors.
  std::uint32_t first_vertex;
  std::uint32_t vertex_count;
};

struct OccupiedVoxel {
  std::uint64_t cell;  // linear index in the grid
  glm::ivec3 coord;
  std::uint32_t first_part = 0;  // into Voxelization::parts
  std::uint32_t part_count = 0;
  float area = 0.0f;  // total triangle area inside the cell
};

struct Voxelization {
  VoxelGrid grid;
  std::vector<OccupiedVoxel> voxels;
  std::vector<TrianglePart> parts;
  std::vector<glm::vec3> part_vertices;
  std::unordered_map<std::uint64_t, std::uint32_t> voxel_of_cell;  // cell -> index in voxels

  // Index into `voxels` of an occupied cell, or -1.
  std::int64_t find(const glm::ivec3& coord) const;
};

// Clips every triangle against the grid's cell planes (exact polygon clipping,
// slab by slab, so a large triangle costs the cells it really crosses).
Voxelization voxelize(const Scene& scene, const VoxelGrid& grid, Progress* progress = nullptr);

// Area of the triangle (a,b,c) inside the axis-aligned box; exact up to
// rounding. Exposed for tests.
float clipped_triangle_area(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                            const Bounds& box);

}  // namespace bounce
