// Exact clipped areas and area conservation of the voxelisation.
#include <gtest/gtest.h>

#include <cmath>

#include "voxel/voxelization.h"

namespace bounce {

namespace {

Scene one_triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  Scene s;
  s.positions = {a, b, c};
  s.triangles = {{0, 1, 2}};
  s.triangle_material = {0};
  s.triangle_mesh = {0};
  s.materials = {Material{}};
  s.meshes = {MeshInfo{"t", "", 0, 1, false, 1.0f}};
  return s;
}

}  // namespace

TEST(ClippedArea, TriangleInsideBoxKeepsItsArea) {
  Bounds box{{-1, -1, -1}, {1, 1, 1}};
  EXPECT_NEAR(clipped_triangle_area({0, 0, 0}, {0.5f, 0, 0}, {0, 0.5f, 0}, box), 0.125f, 1e-6f);
}

TEST(ClippedArea, RightTriangleCutByAPlaneMatchesGeometry) {
  // Right triangle (0,0)-(2,0)-(0,2) in z=0, box x in [0,1]: the part with
  // x <= 1 is the triangle minus the corner triangle (1,0)-(2,0)-(1,1): 2 - 0.5.
  Bounds box{{0, -5, -1}, {1, 5, 1}};
  EXPECT_NEAR(clipped_triangle_area({0, 0, 0}, {2, 0, 0}, {0, 2, 0}, box), 1.5f, 1e-6f);
}

TEST(Voxelize, AreasOfPartsAddUpToTheTriangle) {
  // A slanted triangle crossing many cells.
  const Scene s = one_triangle({0.05f, 0.1f, 0.0f}, {3.9f, 0.3f, 1.7f}, {1.1f, 3.7f, 3.3f});
  const VoxelGrid grid(s.bounds(), 13);
  const Voxelization v = voxelize(s, grid);
  double sum = 0.0;
  for (const auto& part : v.parts) sum += part.area;
  EXPECT_GT(v.voxels.size(), 20u);
  EXPECT_NEAR(sum, s.triangle_area(0), 1e-4 * s.triangle_area(0));
  // Every part really lies in its cell: its clipped area agrees.
  for (const auto& vox : v.voxels) {
    const auto& part = v.parts[vox.first_part];
    const float direct = clipped_triangle_area(s.vertex(0, 0), s.vertex(0, 1), s.vertex(0, 2),
                                               grid.cell_bounds(vox.coord));
    EXPECT_NEAR(part.area, direct, 1e-5f * s.triangle_area(0));
  }
}

TEST(Voxelize, TriangleOnACellPlaneIsCountedOnce) {
  // x = 0.5 is a cell plane of a 2-cell grid over [0,1] once padded and centred.
  Scene s = one_triangle({0.5f, 0, 0}, {0.5f, 1, 0}, {0.5f, 0, 1});
  s.positions.push_back({0, 0, 0});
  s.positions.push_back({1, 1, 1});
  s.triangles.push_back({3, 3, 4});  // degenerate helper widening the bounds to [0,1]^3
  s.triangle_material.push_back(0);
  s.triangle_mesh.push_back(0);
  const Voxelization v = voxelize(s, VoxelGrid(s.bounds(), 2));
  double sum = 0.0;
  for (const auto& part : v.parts)
    if (part.triangle == 0) sum += part.area;
  EXPECT_NEAR(sum, 0.5, 1e-5);
}

TEST(VoxelGrid, RejectsAbsurdResolutions) {
  Bounds b{{0, 0, 0}, {1, 1, 1}};
  EXPECT_THROW(VoxelGrid(b, 0), VoxelGrid::SettingsError);
  EXPECT_THROW(VoxelGrid(b, -3), VoxelGrid::SettingsError);
  EXPECT_THROW(VoxelGrid(b, 100000), VoxelGrid::SettingsError);
}

TEST(VoxelGrid, CellsAreCubicAndCoverTheBounds) {
  Bounds b{{0, 0, 0}, {4, 2, 1}};
  const VoxelGrid g(b, 8);
  EXPECT_EQ(g.dims().x, 8);
  EXPECT_EQ(g.dims().y, 4);
  EXPECT_EQ(g.dims().z, 2);
  for (int a = 0; a < 3; ++a) {
    EXPECT_LT(g.bounds().lo[a], b.lo[a]);
    EXPECT_GT(g.bounds().hi[a], b.hi[a]);
  }
}

}  // namespace bounce
