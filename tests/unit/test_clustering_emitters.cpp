// Virtual patches never mix emitting and non-emitting surface. In the Cornell
// box the ceiling light is a quad 1 cm under the ceiling, facing the same way:
// by normal, colour and position the two are the cheapest merge in their
// voxels, and a patch holding both sends the quad's light out as if from the
// whole patch, most of which (the ceiling above the quad) sees only the
// quad's back (docs/benchmarks.md, "What the figures are made of": rows of 0.35-0.47
// instead of ~0.8, 9% of the indirect light lost at 150 patches). With every
// voxel merged as far as merging goes (one patch per voxel asked), each patch
// must still be all emitter or all not.
#include <gtest/gtest.h>

#include <string>

#include "base/diagnostics.h"
#include "patches/clustering.h"
#include "patches/samples.h"
#include "raytrace/ray_tracer.h"
#include "scene/scene_loader.h"
#include "voxel/voxelization.h"

namespace bounce {
namespace {

bool emits(const Sample& s) {
  return s.emission.r > 0.0f || s.emission.g > 0.0f || s.emission.b > 0.0f;
}

TEST(ClusteringEmitters, EmittersAndTheSurfaceBehindThemStayApart) {
  Diagnostics d;
  const Scene scene = SceneLoader(d).load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-box");
  const RayTracer tracer(scene);
  const Voxelization voxels = voxelize(scene, VoxelGrid(scene.bounds(), 4));
  const SampleSet samples = generate_samples(scene, tracer, voxels, SamplingSettings{});
  std::size_t emitting_samples = 0;
  for (const Sample& s : samples.samples) emitting_samples += emits(s) ? 1 : 0;
  ASSERT_GT(emitting_samples, 0u) << "the box's light must be sampled";
  for (const std::size_t total : {std::size_t{0}, std::size_t{150}}) {
    ClusteringSettings settings;
    settings.patches_per_voxel = 1;
    settings.total_patches = total;
    ClusteringStats stats;
    const PatchSet patches = cluster_virtual_patches(tracer, voxels, samples, settings, stats);
    std::size_t emitting_patches = 0;
    for (std::size_t p = 0; p < patches.size(); ++p) {
      std::size_t emitting = 0, members = 0;
      for (std::uint32_t k = patches.member_first[p]; k < patches.member_first[p + 1]; ++k) {
        emitting += emits(samples.samples[patches.member_samples[k]]) ? 1 : 0;
        ++members;
      }
      EXPECT_TRUE(emitting == 0 || emitting == members)
          << "patch " << p << " mixes " << emitting << " emitting samples with "
          << members - emitting << " others (budget " << total << ")";
      emitting_patches += emitting > 0 ? 1 : 0;
    }
    EXPECT_GT(emitting_patches, 0u);
  }
}

}  // namespace
}  // namespace bounce
