// The reference cache: a hit returns exactly what was stored, a changed
// light or setting misses, and entries land atomically under their key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "raytrace/ray_tracer.h"
#include "reference/reference_cache.h"
#include "scratch_dir.h"
#include "test_scenes.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

using test::ScratchDir;

Scene lit_furnace(float intensity) {
  Scene scene = test_scenes::furnace_box(glm::vec3(0.5f), glm::vec3(0.0f));
  scene.camera = {{0.5f, 0.5f, 0.95f}, {0.5f, 0.5f, 0.0f}, {0, 1, 0}, 60.0f};
  Light l;
  l.position = {0.5f, 0.8f, 0.5f};
  l.intensity = intensity;
  scene.lights.push_back(l);
  return scene;
}

TEST(ReferenceCache, HitReturnsIdenticalImagesAndChangedLightMisses) {
  const ScratchDir dir("bounce-reference-cache");
  const ReferenceCache cache(dir.path());
  ReferenceSettings settings;
  settings.samples = 4;
  const Scene scene = lit_furnace(1.0f);
  const RayTracer tracer(scene);
  const ReferencePathTracer pt(tracer, settings);
  bool hit = true;
  const ReferenceImages first = cached_reference_images(pt, 16, 12, &cache, nullptr, &hit);
  EXPECT_FALSE(hit);
  const ReferenceImages second = cached_reference_images(pt, 16, 12, &cache, nullptr, &hit);
  EXPECT_TRUE(hit);
  EXPECT_EQ(first.samples, second.samples);
  EXPECT_EQ(first.full.pixels, second.full.pixels);
  EXPECT_EQ(first.indirect.pixels, second.indirect.pixels);
  EXPECT_EQ(first.full_variance.pixels, second.full_variance.pixels);
  EXPECT_EQ(first.coverage, second.coverage);
  // No temporary files left behind: exactly one entry.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);

  const Scene brighter = lit_furnace(2.0f);
  const RayTracer tracer2(brighter);
  const ReferencePathTracer pt2(tracer2, settings);
  const ReferenceImages third = cached_reference_images(pt2, 16, 12, &cache, nullptr, &hit);
  EXPECT_FALSE(hit);
  EXPECT_NE(third.full.pixels, first.full.pixels);

  ReferenceSettings more = settings;
  more.samples = 5;
  const ReferencePathTracer pt3(tracer, more);
  cached_reference_images(pt3, 16, 12, &cache, nullptr, &hit);
  EXPECT_FALSE(hit) << "a changed setting must miss";
  // The thread count does not change results, so it shares the entry.
  ReferenceSettings threads = settings;
  threads.threads = 1;
  const ReferencePathTracer pt4(tracer, threads);
  cached_reference_images(pt4, 16, 12, &cache, nullptr, &hit);
  EXPECT_TRUE(hit);
}

TEST(ReferenceCache, PointsRoundTripAndCorruptEntryIsAMiss) {
  const ScratchDir dir("bounce-reference-cache");
  const ReferenceCache cache(dir.path());
  ReferenceSettings settings;
  settings.samples = 3;
  const Scene scene = lit_furnace(1.0f);
  const RayTracer tracer(scene);
  const ReferencePathTracer pt(tracer, settings);
  const std::vector<ReferencePoint> points = {
      {{0.5f, 0.5f, 0.0f}, {0, 0, 1}, glm::vec3(0.5f), glm::vec3(0.0f)},
      {{0.2f, 0.0f, 0.3f}, {0, 1, 0}, glm::vec3(0.5f), glm::vec3(0.0f)}};
  bool hit = true;
  const PointReference a = cached_reference_points(pt, points, &cache, nullptr, &hit);
  EXPECT_FALSE(hit);
  const PointReference b = cached_reference_points(pt, points, &cache, nullptr, &hit);
  EXPECT_TRUE(hit);
  EXPECT_EQ(a.radiosity, b.radiosity);
  EXPECT_EQ(a.indirect_irradiance, b.indirect_irradiance);
  EXPECT_EQ(a.radiosity_variance, b.radiosity_variance);
  // Truncate the entry: the next call must miss and recompute, not crash.
  for (const auto& f : fs::directory_iterator(dir.path())) fs::resize_file(f.path(), 20);
  const PointReference c = cached_reference_points(pt, points, &cache, nullptr, &hit);
  EXPECT_FALSE(hit);
  EXPECT_EQ(c.radiosity, a.radiosity);
}

}  // namespace
}  // namespace bounce
