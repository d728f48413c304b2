// Virtual patches under a total budget (ClusteringSettings::total_patches,
// what `--patches-total` asks for): the cheapest merge of the whole scene is
// taken first, never across voxels, until the budget remains. On the Cornell
// box with the bunny, the walls' flat, evenly lit voxels should end with
// fewer patches than the bunny's, whose samples differ in normal and in what
// they see (the merge metric, docs/method.md 4); a fixed count per voxel gives both
// the same.
#include <gtest/gtest.h>

#include <array>
#include <map>
#include <string>

#include "base/diagnostics.h"
#include "patches/clustering.h"
#include "patches/samples.h"
#include "raytrace/ray_tracer.h"
#include "scene/scene_loader.h"
#include "test_scenes.h"
#include "voxel/voxelization.h"

namespace bounce {
namespace {

struct Sampled {
  Scene scene;
  std::unique_ptr<RayTracer> tracer;
  Voxelization voxels;
  SampleSet samples;
};

const Sampled& cornell_bunny() {
  static const Sampled s = [] {
    Sampled r;
    Diagnostics d;
    r.scene = SceneLoader(d).load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-bunny");
    r.tracer = std::make_unique<RayTracer>(r.scene);
    r.voxels = voxelize(r.scene, VoxelGrid(r.scene.bounds(), 6));
    r.samples = generate_samples(r.scene, *r.tracer, r.voxels, SamplingSettings{});
    return r;
  }();
  return s;
}

std::uint32_t bunny_mesh(const Scene& scene) {
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    if (scene.meshes[m].name == "bunny") return static_cast<std::uint32_t>(m);
  ADD_FAILURE() << "no mesh named bunny";
  return 0;
}

// Mean patches per voxel over voxels whose samples are all on the bunny, and
// over voxels with none on it.
std::pair<double, double> patches_per_voxel(const Sampled& s, const PatchSet& patches) {
  const std::uint32_t bunny = bunny_mesh(s.scene);
  std::map<std::uint32_t, std::size_t> count;
  for (const Patch& p : patches.patches) ++count[p.voxel];
  double on = 0.0, off = 0.0;
  std::size_t n_on = 0, n_off = 0;
  for (const auto& [v, c] : count) {
    std::size_t on_bunny = 0;
    const std::size_t all = s.samples.first[v + 1] - s.samples.first[v];
    for (std::uint32_t k = s.samples.first[v]; k < s.samples.first[v + 1]; ++k)
      on_bunny += s.samples.samples[k].mesh == bunny ? 1 : 0;
    if (on_bunny == all) on += static_cast<double>(c), ++n_on;
    if (on_bunny == 0) off += static_cast<double>(c), ++n_off;
  }
  EXPECT_GT(n_on, 0u);
  EXPECT_GT(n_off, 0u);
  return {on / static_cast<double>(n_on), off / static_cast<double>(n_off)};
}

PatchSet cluster(std::size_t total) {
  const Sampled& s = cornell_bunny();
  ClusteringSettings settings;
  settings.total_patches = total;
  ClusteringStats stats;
  return cluster_virtual_patches(*s.tracer, s.voxels, s.samples, settings, stats);
}

TEST(PatchBudget, KeepsExactlyTheBudgetAndEveryVoxelKeepsAPatch) {
  const Sampled& s = cornell_bunny();
  const std::size_t occupied = s.voxels.voxels.size();
  // Clusters facing more than 90 degrees apart never merge (two sides of a
  // thin wall, the box's edges), so the fewest patches the scene can have is
  // above one per voxel: a budget of 1 gives that floor.
  const std::size_t floor = cluster(1).patches.size();
  EXPECT_GE(floor, occupied);
  for (std::size_t total : {floor + 7, 2 * occupied, 3 * occupied + 1}) {
    ASSERT_GT(total, floor);
    const PatchSet p = cluster(total);
    EXPECT_EQ(p.patches.size(), total);
    std::map<std::uint32_t, std::size_t> per_voxel;
    for (const Patch& q : p.patches) ++per_voxel[q.voxel];
    for (std::size_t v = 0; v < occupied; ++v) {
      if (s.samples.first[v + 1] > s.samples.first[v]) {
        EXPECT_GE(per_voxel[static_cast<std::uint32_t>(v)], 1u) << "voxel " << v;
      }
    }
    // Every sample is in exactly one patch.
    EXPECT_EQ(p.member_samples.size(), s.samples.samples.size());
  }
}

TEST(PatchBudget, CurvedSurfaceKeepsMorePatchesThanFlatWalls) {
  const Sampled& s = cornell_bunny();
  const std::size_t total = 3 * s.voxels.voxels.size();
  const auto [bunny_budget, walls_budget] = patches_per_voxel(s, cluster(total));
  EXPECT_GT(bunny_budget, 1.5 * walls_budget)
      << "bunny voxels " << bunny_budget << " patches, wall voxels " << walls_budget;
  // The per-voxel rule at the same total gives both about the same.
  const auto [bunny_fixed, walls_fixed] = patches_per_voxel(s, cluster(0));
  EXPECT_LT(bunny_fixed, 1.5 * walls_fixed)
      << "bunny voxels " << bunny_fixed << " patches, wall voxels " << walls_fixed;
}

PatchSet cluster_walls(const Sampled& s, std::size_t total, std::vector<float> density) {
  ClusteringSettings settings;
  settings.total_patches = total;
  settings.mesh_density = std::move(density);
  ClusteringStats stats;
  return cluster_virtual_patches(*s.tracer, s.voxels, s.samples, settings, stats);
}

// Two equal unit walls facing each other (z = 0 and z = 1), sampled on a
// 4^3 grid: 16 voxels a wall, each with enough samples for 6 patches.
const Sampled& two_walls() {
  static const Sampled s = [] {
    Sampled r;
    r.scene = test_scenes::parallel_squares();
    r.tracer = std::make_unique<RayTracer>(r.scene);
    r.voxels = voxelize(r.scene, VoxelGrid(r.scene.bounds(), 4));
    SamplingSettings sampling;
    sampling.samples_per_face = 6;
    r.samples = generate_samples(r.scene, *r.tracer, r.voxels, sampling);
    return r;
  }();
  return s;
}

std::array<std::size_t, 2> patches_per_wall(const PatchSet& p) {
  std::array<std::size_t, 2> n{0, 0};
  for (const Patch& q : p.patches) ++n.at(q.mesh);
  return n;
}

TEST(PatchBudget, DensityFourOnOneOfTwoEqualWallsGivesItFourTimesThePatches) {
  const Sampled& s = two_walls();
  ASSERT_EQ(s.scene.meshes.size(), 2u);
  // Every voxel must be able to hold its share (4.8 patches at density 4)
  // and go down to one (1.2 at density 1): otherwise the clamping, not the
  // density, sets the ratio.
  std::size_t fewest_samples = s.samples.samples.size();
  for (std::size_t v = 0; v + 1 < s.samples.first.size(); ++v)
    fewest_samples =
        std::min<std::size_t>(fewest_samples, s.samples.first[v + 1] - s.samples.first[v]);
  ASSERT_GE(fewest_samples, 5u);
  const std::size_t total = 96;  // 3 a voxel over 32 voxels
  const auto even = patches_per_wall(cluster_walls(s, total, {}));
  EXPECT_EQ(even[0] + even[1], total);
  const auto dense = patches_per_wall(cluster_walls(s, total, {4.0f, 1.0f}));
  // The budget is still the budget, to within the one patch each mesh's
  // rounding may add or drop.
  EXPECT_NEAR(static_cast<double>(dense[0] + dense[1]), static_cast<double>(total), 2.0);
  // Each wall keeps 4 (or 1) times what it kept at density 1, scaled back to
  // 96; the walls differ a little at density 1 (the two sides sample
  // differently), so the ratio is measured against that. What moves it off 4:
  // per-mesh rounding (one patch) and the sparse wall's voxels that cannot go
  // below one patch, which keep more than their share. Measured: 52/44 at
  // density 1, 78/18 at density 4, a relative ratio of 3.67; 0.4 allows for
  // that floor and the rounding, and fails if the density is ignored (1) or
  // applied twice (16).
  const double ratio = static_cast<double>(dense[0]) / static_cast<double>(dense[1]);
  const double even_ratio = static_cast<double>(even[0]) / static_cast<double>(even[1]);
  EXPECT_NEAR(ratio / even_ratio, 4.0, 0.4) << "dense wall " << dense[0] << ", other " << dense[1]
                                            << "; at density 1 " << even[0] << " and " << even[1];
  // The other way round, the other wall.
  const auto swapped = patches_per_wall(cluster_walls(s, total, {1.0f, 4.0f}));
  EXPECT_GT(swapped[1], 3 * swapped[0]);
}

TEST(PatchBudget, DensityOneEverywhereIsExactlyNoDensity) {
  const Sampled& s = cornell_bunny();
  for (std::size_t total : {std::size_t{0}, 2 * s.voxels.voxels.size()}) {
    SCOPED_TRACE(total);
    ClusteringSettings a, b;
    a.total_patches = b.total_patches = total;
    b.mesh_density.assign(s.scene.meshes.size(), 1.0f);
    ClusteringStats stats;
    const PatchSet pa = cluster_virtual_patches(*s.tracer, s.voxels, s.samples, a, stats);
    const PatchSet pb = cluster_virtual_patches(*s.tracer, s.voxels, s.samples, b, stats);
    EXPECT_EQ(pa.member_first, pb.member_first);
    EXPECT_EQ(pa.member_samples, pb.member_samples);
  }
}

TEST(PatchBudget, DensityScalesPatchesPerVoxelWithoutABudget) {
  const Sampled& s = two_walls();
  for (std::size_t v = 0; v + 1 < s.samples.first.size(); ++v)
    ASSERT_GE(s.samples.first[v + 1] - s.samples.first[v], 6u) << "voxel " << v;
  const auto n = patches_per_wall(cluster_walls(s, 0, {2.0f, 1.0f}));
  // 16 voxels a wall: 6 patches each on the dense wall, 3 on the other.
  EXPECT_EQ(n[0], 16u * 6u);
  EXPECT_EQ(n[1], 16u * 3u);
}

}  // namespace
}  // namespace bounce
