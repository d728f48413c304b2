#pragma once
// What the shipped textured-floor scene holds by construction, written out
// independently of the loader: its floor (material "floor", 2 x 2) is
// mapped once onto an 8 x 8 checker (checker.png) of two sRGB colours,
// times the floor's Kd 0.9.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <glm/glm.hpp>

#include "patches/samples.h"
#include "raytrace/ray_tracer.h"
#include "scene/scene.h"
#include "voxel/voxelization.h"

namespace bounce::test {

inline const std::filesystem::path kFloorScene =
    std::filesystem::path(BOUNCE_RESOURCE_DIR) / "scenes" / "textured-floor";

// The sRGB transfer function.
inline double decode(int byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// checker.png's two colours (sRGB bytes) times the floor's Kd 0.9, linear.
inline glm::dvec3 colour_a() { return 0.9 * glm::dvec3(decode(224), decode(96), decode(64)); }
inline glm::dvec3 colour_b() { return 0.9 * glm::dvec3(decode(48), decode(128), decode(192)); }

// Every channel within `tolerance`.
inline bool near(const glm::dvec3& a, const glm::dvec3& b, double tolerance) {
  return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::dvec3(tolerance)));
}

// The bake's samples of `s` (on the scene's grid of 8 voxels across) with
// the texture albedo of the surface each carries.
inline SampleSet textured_samples(const Scene& s) {
  const RayTracer tracer(s);
  const Voxelization vox = voxelize(s, VoxelGrid(s.bounds(), 8));
  SampleSet set = generate_samples(s, tracer, vox, SamplingSettings{});
  apply_surface_textures(s, vox, set);
  return set;
}

// The bake's samples on a scene holding the textured floor: the floor's
// tile it, and their area-weighted albedo is the whole floor's mean, the
// mean of the two colours; small ones on one square carry its colour.
// Samples of untextured surfaces keep their material's albedo.
inline void expect_floor_samples_carry_the_checker(const Scene& s) {
  const RayTracer tracer(s);
  const Voxelization vox = voxelize(s, VoxelGrid(s.bounds(), 8));
  SampleSet set = generate_samples(s, tracer, vox, SamplingSettings{});
  EXPECT_GT(apply_surface_textures(s, vox, set), 0u);
  glm::dvec3 sum(0.0), lo(1.0), hi(0.0);
  double area = 0.0;
  for (const Sample& x : set.samples) {
    if (s.material_of(x.triangle).name != "floor") {
      if (!s.textured(x.triangle)) {
        EXPECT_EQ(x.albedo, s.material_of(x.triangle).albedo);
      }
      continue;
    }
    sum += static_cast<double>(x.area) * glm::dvec3(x.albedo);
    area += static_cast<double>(x.area);
    lo = glm::min(lo, glm::dvec3(x.albedo));
    hi = glm::max(hi, glm::dvec3(x.albedo));
  }
  ASSERT_NEAR(area, 4.0, 1e-3);
  const glm::dvec3 mean = sum / area;
  EXPECT_TRUE(near(mean, 0.5 * (colour_a() + colour_b()), 3e-3))
      << mean.x << " " << mean.y << " " << mean.z;
  EXPECT_GT(hi.r - lo.r, 0.2 * (colour_a().r - colour_b().r));
  EXPECT_TRUE(glm::all(glm::greaterThanEqual(lo, glm::min(colour_a(), colour_b()) - 1e-3)));
  EXPECT_TRUE(glm::all(glm::lessThanEqual(hi, glm::max(colour_a(), colour_b()) + 1e-3)));
}

}  // namespace bounce::test
