// The studio's mesh list: it shows each mesh of a bake with the patches the
// bake gave it (counted here from patches.npy, independently of the
// manifest's table the list reads), and a density edited in it reaches the
// re-bake, whose plan re-runs from the patches naming that mesh alone (its
// manifest lists the voxels and samples as reused), while unchanged
// densities reuse the whole bake.
#include <algorithm>
#include <string>
#include <vector>

#include "bake_job.h"
#include "bounce/bake.h"
#include "bounce/bake_folder.h"
#include "mesh_density_panel.h"
#include "render_support.h"
#include "settings_panel.h"

namespace bounce::render_test {

namespace fs = std::filesystem;

namespace {

// Patches per mesh, from the patches themselves.
std::vector<std::size_t> patches_per_mesh(const PatchSet& patches, std::size_t meshes) {
  std::vector<std::size_t> out(meshes, 0);
  for (const Patch& p : patches.patches)
    if (p.mesh < meshes) ++out[p.mesh];
  return out;
}

void expect_rows(const studio::MeshDensityPanel& panel, const Scene& scene,
                 const PatchSet& patches) {
  ASSERT_EQ(panel.mesh_count(), static_cast<int>(scene.meshes.size()));
  const std::vector<std::size_t> counted = patches_per_mesh(patches, scene.meshes.size());
  std::size_t total = 0;
  for (int row = 0; row < panel.mesh_count(); ++row) {
    const auto i = static_cast<std::size_t>(row);
    EXPECT_EQ(panel.mesh_name(row).toStdString(), scene.meshes[i].name);
    EXPECT_EQ(panel.patches(row), counted[i]) << scene.meshes[i].name;
    total += panel.patches(row);
  }
  EXPECT_EQ(total, patches.size());
}

}  // namespace

class MeshDensity : public RenderTest {};

TEST_F(MeshDensity, ListShowsEveryMeshWithItsPatchCount) {
  const auto data = load_fixture();
  ASSERT_NE(data->scene, nullptr);
  studio::MeshDensityPanel panel;
  panel.show_meshes(manifest_meshes(data->bake), false);
  panel.show();
  settle();
  expect_rows(panel, *data->scene, data->bake.patches);
  // The Cornell box's meshes all have density 1; nothing is edited.
  EXPECT_EQ(panel.densities(), std::vector<float>(data->scene->meshes.size(), 1.0f));
  EXPECT_FALSE(panel.edited());
}

TEST_F(MeshDensity, EditedDensityReBakesFromThePatchesNamingTheMesh) {
  const fs::path dir = work_dir("mesh-density");
  const fs::path scene = fs::path(BOUNCE_RESOURCE_DIR) / "scenes" / "cornell-box";
  // The studio's own settings, on a coarse grid.
  studio::SettingsPanel settings_panel;
  settings_panel.set_grid(studio::SettingsPanel::GridChoice::VoxelSize, 2);
  const BakeSettings settings = settings_panel.settings();
  Progress progress;
  auto first = std::make_shared<const studio::BakeJobResult>(
      studio::run_bake_job(scene, settings, dir / "first", progress));

  studio::MeshDensityPanel panel;
  panel.show_meshes(manifest_meshes(first->data->bake), true);
  expect_rows(panel, *first->scene, first->result->patches);
  ASSERT_GE(panel.mesh_count(), 2);

  // Unchanged densities: nothing to run.
  const studio::BakeJobResult same =
      studio::run_bake_job(scene, settings, dir / "same", progress, first, panel.densities());
  EXPECT_EQ(same.result->plan.first, BakeStage::None);

  // One mesh four times as dense: the patches on, one reason naming it.
  panel.set_density(0, 4.0);
  EXPECT_TRUE(panel.edited());
  std::vector<float> expected(first->scene->meshes.size(), 1.0f);
  expected[0] = 4.0f;
  EXPECT_EQ(panel.densities(), expected);
  const std::string name = first->scene->meshes[0].name;
  const studio::BakeJobResult denser =
      studio::run_bake_job(scene, settings, dir / "denser", progress, first, panel.densities());
  EXPECT_EQ(denser.result->plan.first, BakeStage::Patches);
  EXPECT_EQ(denser.result->plan.reasons,
            std::vector<std::string>{"patch density of '" + name + "': 1 -> 4 (re-runs from " +
                                     "patches)"});
  // The manifest's timings: the voxels and samples taken from the first
  // bake, the ray tracer built again for the clustering, which ran.
  std::vector<std::string> stages;
  for (const auto& st : denser.data->bake.manifest.at("stages"))
    stages.push_back(st.at("name").get<std::string>());
  const auto listed = [&stages](const std::string& step) {
    return std::find(stages.begin(), stages.end(), step) != stages.end();
  };
  EXPECT_TRUE(listed("voxelize (reused)")) << testing::PrintToString(stages);
  EXPECT_TRUE(listed("sample (reused)")) << testing::PrintToString(stages);
  EXPECT_TRUE(listed("ray tracer (BVH build)")) << testing::PrintToString(stages);
  EXPECT_TRUE(listed("patches")) << testing::PrintToString(stages);
  EXPECT_TRUE(listed("form factors")) << testing::PrintToString(stages);
  EXPECT_FALSE(listed("voxelize")) << testing::PrintToString(stages);
  // The bake used it: its manifest says so, and the mesh's voxels kept more
  // patches (a fixed count per voxel, times the voxel's area-weighted
  // density; at this coarse grid the extra patches of a voxel may go to the
  // other meshes sharing it, so the total is what must grow).
  const std::vector<ManifestMesh> after = manifest_meshes(denser.data->bake);
  ASSERT_EQ(after.size(), expected.size());
  EXPECT_EQ(after[0].patch_density, 4.0f);
  for (std::size_t i = 1; i < after.size(); ++i) EXPECT_EQ(after[i].patch_density, 1.0f);
  EXPECT_GT(denser.result->patches.size(), first->result->patches.size());
  // The previous job's scene is left as its bake had it.
  EXPECT_EQ(first->scene->meshes[0].patch_density, 1.0f);

  // Shown again, the list has the new counts and nothing edited.
  panel.show_meshes(after, true);
  expect_rows(panel, *denser.scene, denser.result->patches);
  EXPECT_FALSE(panel.edited());
}

TEST_F(MeshDensity, DensitiesThatDoNotFitTheSceneAreOneErrorNamingIt) {
  const fs::path dir = work_dir("mesh-density-errors");
  const fs::path scene = fs::path(BOUNCE_RESOURCE_DIR) / "scenes" / "cornell-box";
  studio::SettingsPanel settings_panel;
  settings_panel.set_grid(studio::SettingsPanel::GridChoice::VoxelSize, 2);
  Progress progress;
  try {
    studio::run_bake_job(scene, settings_panel.settings(), dir / "bake", progress, {},
                         {1.0f, 2.0f});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(scene.string()), std::string::npos) << what;
    EXPECT_NE(what.find("2 patch densities given for a scene of"), std::string::npos) << what;
  }
}

}  // namespace bounce::render_test
