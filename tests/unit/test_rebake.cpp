// Re-baking only what a settings change affects (core/bake/rebake_plan.h):
// the plan for each setting against the pipeline's dependencies, and a
// partial re-bake equal to a full bake with the same settings while the
// stages before the change do not run again (counted from the progress
// stages the core reports).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "bake/bake.h"
#include "bake/rebake_plan.h"
#include "scene/scene_loader.h"

namespace bounce {
namespace {

const Scene& cornell_box() {
  static const Scene scene = [] {
    Diagnostics d;
    return SceneLoader(d).load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-box");
  }();
  return scene;
}

BakeSettings small_settings() {
  BakeSettings s;
  s.voxel_resolution = 3;
  s.codec = CodecChoice::LightWeighted;
  s.kept_fraction = 0.04;
  s.transport.bounces = 3;
  s.transport.backend = TransportSettings::Backend::OpenBLAS;
  s.pictures = false;
  return s;
}

// The previous bake's settings as the Baker resolves them.
BakeSettings resolved(BakeSettings s) {
  s.apply_scene_defaults(cornell_box().defaults);
  return s;
}

BakeStage first_stage(const BakeSettings& next) {
  return plan_rebake(cornell_box(), resolved(small_settings()), next).first;
}

TEST(RebakePlan, EachSettingReRunsFromTheStageItFeeds) {
  const BakeSettings base = small_settings();
  EXPECT_EQ(first_stage(base), BakeStage::None);

  // Writer-only settings run nothing.
  BakeSettings s = base;
  s.dump_matrices = true;
  s.pictures = true;
  EXPECT_EQ(first_stage(s), BakeStage::None);

  // Storage: compression only.
  s = base;
  s.codec = CodecChoice::LargestEntries;
  EXPECT_EQ(first_stage(s), BakeStage::Compress);
  s = base;
  s.kept_fraction = 0.08;
  EXPECT_EQ(first_stage(s), BakeStage::Compress);
  s = base;
  s.kept_fraction.reset();
  s.error_budget = 0.1;
  EXPECT_EQ(first_stage(s), BakeStage::Compress);
  s = base;
  s.ordering = OrderingMethod::GreedyRowTour;
  EXPECT_EQ(first_stage(s), BakeStage::Compress);

  // Bounces and the GEMM backend: transport and compression.
  s = base;
  s.transport.bounces = TransportSettings::kInfiniteBounces;
  EXPECT_EQ(first_stage(s), BakeStage::Transport);
  s = base;
  s.transport.backend = TransportSettings::Backend::Auto;
  EXPECT_EQ(first_stage(s), BakeStage::Transport);
  // Two changes: the earlier stage wins, and both are named.
  s = base;
  s.transport.bounces = 5;
  s.codec = CodecChoice::Dense;
  const RebakePlan both = plan_rebake(cornell_box(), resolved(base), s);
  EXPECT_EQ(both.first, BakeStage::Transport);
  EXPECT_EQ(both.reasons.size(), 2u);
  EXPECT_TRUE(both.runs(BakeStage::Compress));
  EXPECT_FALSE(both.runs(BakeStage::Geometry));

  // What changes the voxels or samples: the whole bake.
  s = base;
  s.voxel_resolution = 4;
  EXPECT_EQ(first_stage(s), BakeStage::Geometry);
  s = base;
  s.samples_per_face = 3;
  EXPECT_EQ(first_stage(s), BakeStage::Geometry);
  s = base;
  s.seed = 7;
  EXPECT_EQ(first_stage(s), BakeStage::Geometry);
  // What the clustering reads: the patches on, on the same samples.
  s = base;
  s.patches_per_voxel = 2;
  EXPECT_EQ(first_stage(s), BakeStage::Patches);
  s = base;
  s.patch_mode = PatchMode::Voxel;
  EXPECT_EQ(first_stage(s), BakeStage::Patches);
  // New visibility changes which patches the checks prune, so the form
  // factors need the unpruned patches again; so do the closure and gather.
  s = base;
  s.visibility_rays = 4;
  EXPECT_EQ(first_stage(s), BakeStage::Patches);
  s = base;
  s.closure_rays = 0;
  EXPECT_EQ(first_stage(s), BakeStage::Patches);
  s = base;
  s.final_gather_rays = 16;
  EXPECT_EQ(first_stage(s), BakeStage::Patches);
  // With a grid change too, the grid wins.
  s.voxel_resolution = 4;
  EXPECT_EQ(first_stage(s), BakeStage::Geometry);
}

TEST(RebakePlan, EachChangedPatchDensityIsOneReasonNamingItsMesh) {
  const BakeSettings previous = resolved(small_settings());
  const std::vector<float> baked = patch_densities(cornell_box());
  ASSERT_GE(baked.size(), 4u);
  EXPECT_EQ(plan_rebake(cornell_box(), previous, baked, small_settings()).first, BakeStage::None);
  Scene edited = cornell_box();
  edited.meshes[1].patch_density = 2.0f;
  edited.meshes[3].patch_density = 0.5f;
  const RebakePlan plan = plan_rebake(edited, previous, baked, small_settings());
  EXPECT_EQ(plan.first, BakeStage::Patches);
  EXPECT_EQ(
      plan.reasons,
      (std::vector<std::string>{
          "patch density of '" + edited.meshes[1].name + "': 1 -> 2 (re-runs from patches)",
          "patch density of '" + edited.meshes[3].name + "': 1 -> 0.5 (re-runs from patches)"}));
  // A grid change as well: from geometry, every reason kept.
  BakeSettings finer = small_settings();
  finer.voxel_resolution = 4;
  const RebakePlan both = plan_rebake(edited, previous, baked, finer);
  EXPECT_EQ(both.first, BakeStage::Geometry);
  EXPECT_EQ(both.reasons.size(), 3u);
  // Densities of another number of meshes: not this scene's bake.
  const RebakePlan other = plan_rebake(cornell_box(), previous, {1.0f}, small_settings());
  EXPECT_EQ(other.first, BakeStage::Geometry);
  ASSERT_EQ(other.reasons.size(), 1u);
  EXPECT_EQ(other.reasons[0], "patch densities of " + std::to_string(baked.size()) +
                                  " meshes, the previous bake had 1 (re-runs from geometry)");
}

TEST(RebakePlan, APatchTargetThatResolvesToTheSameGridReRunsNothing) {
  const Scene& scene = cornell_box();
  BakeSettings by_target = small_settings();
  by_target.voxel_resolution.reset();
  by_target.patches_total = 150;
  BakeSettings previous = resolved(by_target);
  const int r = Baker::resolution_for_patch_count(scene, 150, *previous.patches_per_voxel,
                                                  previous.patch_mode);
  previous.voxel_resolution = r;  // as the Baker fills it in
  EXPECT_EQ(plan_rebake(scene, previous, by_target).first, BakeStage::None);
  BakeSettings same_grid = small_settings();
  same_grid.voxel_resolution = r;
  EXPECT_EQ(plan_rebake(scene, previous, same_grid).first, BakeStage::None);
  same_grid.voxel_resolution = r + 1;
  EXPECT_EQ(plan_rebake(scene, previous, same_grid).first, BakeStage::Geometry);
}

struct CountedBake {
  BakeResult result;
  std::multiset<std::string> stages;  // every progress stage the core began
};

CountedBake run_bake(const BakeSettings& settings, const BakeResult* previous = nullptr,
                     const Scene& scene = cornell_box()) {
  CountedBake b;
  std::string last;
  Progress progress([&](const std::string& stage, double) {
    if (stage != last) b.stages.insert(stage);
    last = stage;
    return true;
  });
  Diagnostics d;
  b.result = Baker(scene, settings, d).run(progress, previous);
  return b;
}

void expect_same_storage(const MatrixStorage& a, const MatrixStorage& b) {
  ASSERT_EQ(a.codec, b.codec);
  ASSERT_TRUE(a.compressed && b.compressed);
  const CompressedMatrix &x = *a.compressed, &y = *b.compressed;
  EXPECT_EQ(x.ordering, y.ordering);
  EXPECT_EQ(x.encoder, y.encoder);
  EXPECT_EQ(x.permutation, y.permutation);
  EXPECT_EQ(x.blocks, y.blocks);  // bit-exact
  ASSERT_EQ(x.kept.size(), y.kept.size());
  for (std::size_t c = 0; c < x.kept.size(); ++c) {
    EXPECT_EQ(x.kept[c].value, y.kept[c].value);
    EXPECT_EQ(x.kept[c].col, y.kept[c].col);
  }
  EXPECT_EQ(a.errors.matrix.rel_frobenius, b.errors.matrix.rel_frobenius);
  EXPECT_EQ(a.errors.matrix.max_abs, b.errors.matrix.max_abs);
  EXPECT_EQ(a.abs_error_sum, b.abs_error_sum);
}

bool ran(const CountedBake& b, const std::string& prefix) {
  for (const std::string& s : b.stages)
    if (s.rfind(prefix, 0) == 0) return true;
  return false;
}

TEST(Rebake, CodecOnlyReBakeEqualsAFullBakeWithoutNewFormFactors) {
  const CountedBake first = run_bake(small_settings());
  ASSERT_TRUE(ran(first, "form factors"));  // the counting sees the stages
  ASSERT_TRUE(ran(first, "transport"));

  BakeSettings paper = small_settings();
  paper.codec = CodecChoice::LargestEntries;
  paper.ordering = OrderingMethod::GreedyRowTour;
  const CountedBake partial = run_bake(paper, &first.result);
  const CountedBake full = run_bake(paper);

  EXPECT_EQ(partial.result.plan.first, BakeStage::Compress);
  EXPECT_FALSE(ran(partial, "voxelize"));
  EXPECT_FALSE(ran(partial, "form factors"));
  EXPECT_FALSE(ran(partial, "transport"));
  EXPECT_TRUE(ran(partial, "compress"));
  EXPECT_EQ(partial.result.storage.compressed->ordering, "paper-1-pass");
  expect_same_storage(partial.result.storage, full.result.storage);
  EXPECT_EQ(partial.result.settings.voxel_resolution, full.result.settings.voxel_resolution);
  // Reused stages are listed as such; the first bake's storage differs.
  bool reused_form_factors = false;
  for (const StageStats& s : partial.result.stages)
    reused_form_factors |= s.name == "form factors (reused)";
  EXPECT_TRUE(reused_form_factors);
  EXPECT_NE(first.result.storage.compressed->codec, partial.result.storage.compressed->codec);
}

const Scene& textured_floor() {
  static const Scene scene = [] {
    Diagnostics d;
    return SceneLoader(d).load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/textured-floor");
  }();
  return scene;
}

std::vector<std::string> stage_names(const BakeResult& r) {
  std::vector<std::string> names;
  for (const StageStats& s : r.stages) names.push_back(s.name);
  return names;
}

// Field by field: Patch has padding, so no memcmp.
void expect_same_patches(const PatchSet& a, const PatchSet& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t p = 0; p < a.size(); ++p) {
    const Patch &x = a.patches[p], &y = b.patches[p];
    EXPECT_EQ(x.position, y.position) << p;
    EXPECT_EQ(x.normal, y.normal) << p;
    EXPECT_EQ(x.albedo, y.albedo) << p;
    EXPECT_EQ(x.emission, y.emission) << p;
    EXPECT_EQ(x.area, y.area) << p;
    EXPECT_EQ(x.voxel, y.voxel) << p;
    EXPECT_EQ(x.mesh, y.mesh) << p;
  }
  EXPECT_EQ(a.member_first, b.member_first);
  EXPECT_EQ(a.member_samples, b.member_samples);
}

// The textured floor (textures, an alpha mask, three meshes) so that the
// texture step is among those reused; the fence denser.
TEST(Rebake, APatchDensityChangeReusesTheSamplesAndEqualsAFullBake) {
  const Scene& scene = textured_floor();
  ASSERT_FALSE(scene.triangle_uv.empty());
  BakeSettings settings = small_settings();
  settings.voxel_resolution = 4;
  const CountedBake first = run_bake(settings, nullptr, scene);
  ASSERT_TRUE(ran(first, "voxelize"));  // the counting sees the stages
  EXPECT_EQ(first.result.patch_density, patch_densities(scene));

  // The same scene with one mesh denser, as after an edit of scene.json or
  // the studio's mesh list; the settings are unchanged, so only the
  // densities can tell.
  Scene denser = scene;
  std::size_t fence = denser.meshes.size();
  for (std::size_t i = 0; i < denser.meshes.size(); ++i)
    if (denser.meshes[i].name == "fence") fence = i;
  ASSERT_LT(fence, denser.meshes.size());
  denser.meshes[fence].patch_density = 4.0f;
  const CountedBake partial = run_bake(settings, &first.result, denser);
  const CountedBake full = run_bake(settings, nullptr, denser);

  EXPECT_EQ(partial.result.plan.first, BakeStage::Patches);
  EXPECT_EQ(partial.result.plan.reasons,
            std::vector<std::string>{"patch density of 'fence': 1 -> 4 (re-runs from patches)"});
  // The voxels and samples were not made again; the clustering and all
  // after it ran.
  for (const char* stage : {"voxelize", "sample", "surface textures"}) {
    EXPECT_TRUE(ran(full, stage)) << stage;
    EXPECT_FALSE(ran(partial, stage)) << stage;
  }
  EXPECT_TRUE(ran(partial, "cluster: merge samples"));
  EXPECT_TRUE(ran(partial, "form factors"));
  EXPECT_TRUE(ran(partial, "transport"));
  EXPECT_EQ(stage_names(partial.result),
            (std::vector<std::string>{"voxelize (reused)", "sample (reused)", "texture (reused)",
                                      "ray tracer (BVH build)", "patches", "form factors", "checks",
                                      "closure", "balance", "final gather", "light probes",
                                      "evaluation lights", "transport", "compress"}));

  // Equal to a full bake with the new density, bit for bit.
  EXPECT_EQ(partial.result.patch_density, full.result.patch_density);
  EXPECT_EQ(partial.result.patch_density[fence], 4.0f);
  expect_same_patches(partial.result.patches, full.result.patches);
  EXPECT_EQ(partial.result.patches_before_pruning, full.result.patches_before_pruning);
  EXPECT_EQ(partial.result.patch_of_sample, full.result.patch_of_sample);
  EXPECT_EQ(partial.result.form_factors.values, full.result.form_factors.values);
  EXPECT_EQ(partial.result.closure.closure, full.result.closure.closure);
  ASSERT_EQ(partial.result.transport.channels.size(), full.result.transport.channels.size());
  for (std::size_t c = 0; c < full.result.transport.channels.size(); ++c)
    EXPECT_EQ(partial.result.transport.channels[c].t, full.result.transport.channels[c].t);
  expect_same_storage(partial.result.storage, full.result.storage);
  EXPECT_EQ(partial.result.probe.first_hit, full.result.probe.first_hit);
  // The density did change the patches: the fence has more.
  const auto fence_patches = [fence](const PatchSet& p) {
    return std::ranges::count_if(p.patches, [fence](const Patch& x) { return x.mesh == fence; });
  };
  EXPECT_GT(fence_patches(partial.result.patches), fence_patches(first.result.patches));

  // Unchanged densities still reuse everything.
  const CountedBake same = run_bake(settings, &partial.result, denser);
  EXPECT_EQ(same.result.plan.first, BakeStage::None);
  // A re-bake of the re-bake lists each step once, reused or not: the
  // tracer the re-bake built is reused like the rest.
  BakeSettings more = settings;
  more.transport.bounces = 5;
  const CountedBake after = run_bake(more, &partial.result, denser);
  EXPECT_EQ(after.result.plan.first, BakeStage::Transport);
  EXPECT_EQ(stage_names(after.result),
            (std::vector<std::string>{
                "voxelize (reused)", "sample (reused)", "texture (reused)",
                "ray tracer (BVH build) (reused)", "patches (reused)", "form factors (reused)",
                "checks (reused)", "closure (reused)", "balance (reused)", "final gather (reused)",
                "light probes (reused)", "evaluation lights (reused)", "transport", "compress"}));
}

// Another number of meshes than the previous bake had is another scene:
// from geometry.
TEST(Rebake, DensitiesOfAnotherSceneReRunFromGeometry) {
  const CountedBake first = run_bake(small_settings());
  BakeResult other = first.result;
  other.patch_density.pop_back();
  const CountedBake again = run_bake(small_settings(), &other);
  EXPECT_EQ(again.result.plan.first, BakeStage::Geometry);
  EXPECT_TRUE(ran(again, "voxelize"));
}

TEST(Rebake, BouncesReBakeReRunsTransportOnly) {
  const CountedBake first = run_bake(small_settings());
  BakeSettings more = small_settings();
  more.transport.bounces = TransportSettings::kInfiniteBounces;
  const CountedBake partial = run_bake(more, &first.result);
  const CountedBake full = run_bake(more);
  EXPECT_EQ(partial.result.plan.first, BakeStage::Transport);
  EXPECT_FALSE(ran(partial, "form factors"));
  EXPECT_TRUE(ran(partial, "transport"));
  ASSERT_EQ(partial.result.transport.channels.size(), full.result.transport.channels.size());
  for (std::size_t c = 0; c < full.result.transport.channels.size(); ++c)
    EXPECT_EQ(partial.result.transport.channels[c].t, full.result.transport.channels[c].t);
  EXPECT_NE(first.result.transport.channels[0].t, partial.result.transport.channels[0].t);
  expect_same_storage(partial.result.storage, full.result.storage);
  EXPECT_EQ(partial.result.probe.channel_of_rgb, full.result.probe.channel_of_rgb);
}

}  // namespace
}  // namespace bounce
