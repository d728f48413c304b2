// Area lights on the Cornell box's patches: the direct light from a few
// shadow rays per sample (closed-form form factor times sampled visibility)
// against an independent estimate with many rays (the emitter sampled
// whole, as a textured emitter is, with a constant texture).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "base/diagnostics.h"
#include "patches/clustering.h"
#include "patches/samples.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_light_cache.h"
#include "runtime/area_lights.h"
#include "runtime/carried_polygon_frames.h"
#include "runtime/direct_light.h"
#include "scene/scene_loader.h"
#include "scene/texture.h"
#include "voxel/voxelization.h"

namespace bounce {
namespace {

// The same lights, each sampled whole with a constant texture equal to its
// exitance: plain stratified Monte Carlo over the emitter.
std::vector<AreaLight> sampled_whole(std::vector<AreaLight> lights) {
  auto white = std::make_shared<Texture>();
  white->levels.push_back(Texture::Level{1, 1, {glm::vec3(1.0f)}});
  white->mean = glm::vec3(1.0f);
  for (AreaLight& l : lights) {
    l.emission_texture = white;
    l.emission_factor = l.exitance;
  }
  return lights;
}

// Relative RMS difference of the patches' irradiance (green), weighted by
// patch area.
double relative_rms(const std::vector<glm::vec3>& e, const std::vector<glm::vec3>& reference,
                    const PatchSet& patches) {
  double err = 0.0, norm = 0.0;
  for (std::size_t p = 0; p < e.size(); ++p) {
    const double a = patches.patches[p].area;
    const double d = e[p].y - reference[p].y;
    err += a * d * d;
    norm += a * reference[p].y * reference[p].y;
  }
  return std::sqrt(err / norm);
}

// The Cornell box's samples and patches at grid `resolution`, about
// `patches` of them.
struct CornellPatches {
  CornellPatches(int resolution, std::size_t total)
      : scene(SceneLoader(diagnostics)
                  .load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-box")),
        tracer(scene),
        voxels(voxelize(scene, VoxelGrid(scene.bounds(), resolution))),
        samples(generate_samples(scene, tracer, voxels, SamplingSettings{})) {
    ClusteringSettings settings;
    settings.total_patches = total;
    ClusteringStats stats;
    patches = cluster_virtual_patches(tracer, voxels, samples, settings, stats);
  }
  Diagnostics diagnostics;
  Scene scene;
  RayTracer tracer;
  Voxelization voxels;
  SampleSet samples;
  PatchSet patches;
};

TEST(AreaLightPatches, FewRaysPerSampleMatchTheWholeEmitterSampledDensely) {
  const CornellPatches c(16, 2000);
  const RayTracer& tracer = c.tracer;
  const SampleSet& samples = c.samples;
  const PatchSet& patches = c.patches;
  const std::vector<AreaLight> area = area_lights(c.scene);
  ASSERT_EQ(area.size(), 2u);
  const std::vector<AreaLight> whole = sampled_whole(area);
  // 24 x 24 rays per sample and triangle: the reference's own error is a
  // few times below the figures compared.
  const auto reference = direct_irradiance(tracer, samples, patches, {}, whole, 24);
  const double whole_4 =
      relative_rms(direct_irradiance(tracer, samples, patches, {}, whole, 4), reference, patches);
  const double ours =
      relative_rms(direct_irradiance(tracer, samples, patches, {}, area), reference, patches);
  const double ours_2 =
      relative_rms(direct_irradiance(tracer, samples, patches, {}, area, 2), reference, patches);
  // Measured: 0.0072 (whole, 4 x 4), 0.0070 (ours, 3 x 3), 0.0118 (2 x 2).
  EXPECT_LT(whole_4, 0.012) << "the whole-emitter estimate itself";
  EXPECT_LE(ours, 1.1 * whole_4) << kAreaStrata << " x " << kAreaStrata << " rays";
  EXPECT_LT(ours, ours_2) << "more rays, closer";
}

// Caching: a second frame with the same area lights gives the same light
// without working it out again; moving an emitter works it out again.
TEST(AreaLightPatches, TheCacheKeepsTheLightUntilAnEmitterChanges) {
  const CornellPatches c(8, 300);
  const RayTracer& tracer = c.tracer;
  const SampleSet& samples = c.samples;
  const PatchSet& patches = c.patches;
  std::vector<AreaLight> area = area_lights(c.scene);
  const auto frames = carried_polygon_frames(samples);
  AreaLightCache cache;
  std::vector<glm::vec3> first(patches.size()), second(patches.size()), uncached(patches.size());
  direct_irradiance(tracer, samples, frames, patches, {}, area, kAreaStrata, first, {}, &cache);
  direct_irradiance(tracer, samples, frames, patches, {}, area, kAreaStrata, second, {}, &cache);
  direct_irradiance(tracer, samples, frames, patches, {}, area, kAreaStrata, uncached);
  EXPECT_EQ(cache.computed(), 1u);
  EXPECT_EQ(first, second);
  EXPECT_EQ(first, uncached);
  // Twice the exitance: worked out again, twice the light.
  for (AreaLight& l : area) l.exitance *= 2.0f;
  direct_irradiance(tracer, samples, frames, patches, {}, area, kAreaStrata, second, {}, &cache);
  EXPECT_EQ(cache.computed(), 2u);
  for (std::size_t p = 0; p < patches.size(); ++p)
    EXPECT_NEAR(second[p].y, 2.0f * first[p].y, 1e-5f * (1.0f + second[p].y)) << "patch " << p;
}

}  // namespace
}  // namespace bounce
