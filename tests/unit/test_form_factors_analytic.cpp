// Analytic form factors through the real pipeline (scene -> voxels -> samples
// -> virtual patches -> F), summed area-weighted over the patches of each
// surface. References: Howell's catalogue C-11 (parallel opposed unit squares
// at distance 1: 0.199825), C-14 (perpendicular unit squares sharing an edge:
// 0.200044), and coaxial parallel disks r1 = 0.1, r2 = 0.2, h = 0.5: 0.1339.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "bake/bake.h"
#include "scene/scene_loader.h"

namespace bounce {

namespace {

Scene load(const std::string& name) {
  Diagnostics d;
  return SceneLoader(d).load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/" + name);
}

std::uint32_t mesh_index(const Scene& s, const std::string& name) {
  for (std::size_t m = 0; m < s.meshes.size(); ++m)
    if (s.meshes[m].name == name) return static_cast<std::uint32_t>(m);
  ADD_FAILURE() << "no mesh named " << name;
  return 0;
}

// F from every patch of mesh `from` to every patch of mesh `to`, area-weighted.
double surface_form_factor(const BakeResult& r, std::uint32_t from, std::uint32_t to) {
  double area = 0.0, sum = 0.0;
  for (std::size_t p = 0; p < r.patches.size(); ++p) {
    if (r.patches.patches[p].mesh != from) continue;
    area += r.patches.patches[p].area;
    for (std::size_t q = 0; q < r.patches.size(); ++q)
      if (r.patches.patches[q].mesh == to) sum += r.patches.patches[p].area * r.form_factors(p, q);
  }
  return sum / area;
}

BakeResult bake(const Scene& scene, int voxel, int samples_per_face = 4) {
  BakeSettings s;
  s.voxel_resolution = voxel;
  s.samples_per_face = samples_per_face;
  Diagnostics d;
  Progress p;
  return Baker(scene, s, d).run(p);
}

}  // namespace

TEST(AnalyticFormFactors, ParallelUnitSquaresAtDistanceOne) {
  const Scene s = load("parallel-squares");
  const BakeResult r = bake(s, 8);
  const double f = surface_form_factor(r, mesh_index(s, "bottom"), mesh_index(s, "top"));
  std::printf("parallel squares: F = %.6f (reference 0.199825)\n", f);
  EXPECT_NEAR(f, 0.199825, 0.02 * 0.199825) << "F = " << f;
  EXPECT_NEAR(surface_form_factor(r, mesh_index(s, "top"), mesh_index(s, "bottom")), 0.199825,
              0.02 * 0.199825);
}

TEST(AnalyticFormFactors, PerpendicularUnitSquaresSharingAnEdge) {
  const Scene s = load("perpendicular-squares");
  const BakeResult r = bake(s, 8);
  const double f = surface_form_factor(r, mesh_index(s, "floor"), mesh_index(s, "wall"));
  std::printf("perpendicular squares: F = %.6f (reference 0.200044)\n", f);
  EXPECT_NEAR(f, 0.200044, 0.02 * 0.200044) << "F = " << f;
}

TEST(AnalyticFormFactors, CoaxialDisks) {
  // The reference: F_12 = (X - sqrt(X^2 - 4 (R2/R1)^2)) / 2 with
  // R_i = r_i / h, X = 1 + (1 + R2^2) / R1^2.
  const double R1 = 0.1 / 0.5, R2 = 0.2 / 0.5;
  const double X = 1.0 + (1.0 + R2 * R2) / (R1 * R1);
  const double expected = 0.5 * (X - std::sqrt(X * X - 4.0 * (R2 / R1) * (R2 / R1)));
  ASSERT_NEAR(expected, 0.1339, 5e-4);
  const Scene s = load("coaxial-disks");
  const BakeResult r = bake(s, 16);
  const double f = surface_form_factor(r, mesh_index(s, "small"), mesh_index(s, "large"));
  std::printf("coaxial disks: F = %.6f (reference %.6f)\n", f, expected);
  EXPECT_NEAR(f, expected, 0.03 * expected) << "F = " << f;
}

TEST(AnalyticFormFactors, ReciprocityHoldsAndClosedFurnaceRowsSumToOne) {
  const BakeResult r = bake(load("furnace"), 6);
  // Far pairs are reciprocal by construction; near pairs are two quadratures
  // of the same double integral, one per direction, and may differ by their
  // quadrature error, which we hold to the closure tolerance.
  EXPECT_LT(r.checks.reciprocity_error_rel, 0.02);
  EXPECT_EQ(r.checks.non_finite, 0u);
  for (std::size_t p = 0; p < r.patches.size(); ++p) {
    double row = 0.0;
    for (std::size_t q = 0; q < r.patches.size(); ++q) row += r.form_factors(p, q);
    EXPECT_NEAR(row, 1.0, 0.02) << "patch " << p;
  }
}

}  // namespace bounce
