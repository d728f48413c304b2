// The exact patch values the report measures each patch layout with
// (report/exact_patch_light.h), against the white furnace's closed form: in
// a closed box whose walls all emit E with albedo rho, every point receives
// indirect irradiance rho E / (1 - rho) (ReferencePathTracer's furnace test),
// so every patch's indirect exitance is rho^2 E / (1 - rho) per channel,
// whatever the layout: 1.633, 0.5 and 0.129 for rho = (0.7, 0.5, 0.3).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bake/bake.h"
#include "raytrace/ray_tracer.h"
#include "reference/path_tracer.h"
#include "report/exact_patch_light.h"
#include "test_scenes.h"

namespace bounce {
namespace {

TEST(ExactPatchLight, FurnacePatchesGetRhoSquaredEOverOneMinusRho) {
  const glm::vec3 rho(0.7f, 0.5f, 0.3f);
  const Scene scene = test_scenes::furnace_box(rho, glm::vec3(1.0f));
  BakeSettings settings;
  settings.voxel_resolution = 3;
  settings.patch_mode = PatchMode::Virtual;
  settings.codec = CodecChoice::Dense;
  settings.pictures = false;
  Diagnostics diag;
  Progress progress;
  const BakeResult bake = Baker(scene, settings, diag).run(progress);
  ASSERT_GT(bake.patches.size(), 20u);
  const RayTracer tracer(scene);
  ReferenceSettings rs;
  rs.samples = 400;
  const ReferencePathTracer pt(tracer, rs);
  const ExactPatchLight exact =
      exact_patch_indirect(pt, bake.samples, bake.patches, nullptr, &progress);
  ASSERT_EQ(exact.indirect.size(), bake.patches.size());
  ASSERT_EQ(exact.variance.size(), bake.patches.size());
  // The patch values are the area- and albedo-weighted means of the
  // reference at the patch's samples: recomputed here from the path
  // tracer's own estimates at the samples (deterministic, same seed).
  std::vector<ReferencePoint> points;
  for (const Sample& s : bake.samples.samples)
    points.push_back({s.position, s.normal, s.albedo, glm::vec3(0.0f)});
  const PointReference at_samples = pt.estimate_points(points);
  for (std::size_t p = 0; p < bake.patches.size(); ++p) {
    glm::dvec3 sum(0.0), var(0.0);
    double area = 0.0;
    for (std::uint32_t k = bake.patches.member_first[p]; k < bake.patches.member_first[p + 1];
         ++k) {
      const std::uint32_t si = bake.patches.member_samples[k];
      const double a = bake.samples.samples[si].area;
      sum += a * glm::dvec3(rho) * glm::dvec3(at_samples.indirect_irradiance[si]);
      var += a * a * glm::dvec3(rho * rho) * glm::dvec3(at_samples.indirect_variance[si]);
      area += a;
    }
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(exact.indirect[p][c], sum[c] / area, 1e-5 * sum[c] / area) << "patch " << p;
      EXPECT_NEAR(exact.variance[p][c], var[c] / (area * area), 1e-4 * var[c] / (area * area))
          << "patch " << p;
    }
  }
  // Against the closed form: every patch within 5 standard errors of its
  // own estimate (its samples' variances, combined as the value is), and
  // the area-weighted mean over the patches within 2%.
  double weighted = 0.0, total_area = 0.0;
  for (std::size_t p = 0; p < exact.indirect.size(); ++p) {
    for (int c = 0; c < 3; ++c) {
      const double expected = rho[c] * rho[c] / (1.0 - rho[c]);
      const double sigma = std::sqrt(static_cast<double>(exact.variance[p][c]));
      EXPECT_GT(sigma, 0.0) << "patch " << p;
      EXPECT_NEAR(exact.indirect[p][c], expected, 5.0 * sigma) << "patch " << p << " channel " << c;
    }
    weighted += bake.patches.patches[p].area * exact.indirect[p].g;
    total_area += bake.patches.patches[p].area;
  }
  EXPECT_NEAR(weighted / total_area, 0.5, 0.01);
}

}  // namespace
}  // namespace bounce
