// The bake's content key (core/bake/bake_key.h): stable when the scene folder
// is copied elsewhere, changed by one byte of a mesh or material file, by one
// setting or one mesh's density; a folder's stored key only for a complete,
// readable bake; and the Baker's per-stage hook.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include "bake/bake.h"
#include "bake/bake_key.h"
#include "bake/bake_writer.h"
#include "bake/rebake_plan.h"
#include "scene/scene_files.h"
#include "scene/scene_loader.h"
#include "scratch_dir.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

const fs::path kTexturedFloor = fs::path(BOUNCE_RESOURCE_DIR) / "scenes" / "textured-floor";
const fs::path kCornellBox = fs::path(BOUNCE_RESOURCE_DIR) / "scenes" / "cornell-box";

Scene load(const fs::path& path) {
  Diagnostics d;
  return SceneLoader(d).load(path);
}

std::string key_of(const fs::path& scene, const BakeSettings& settings = {}) {
  const std::optional<std::string> key = bake_key(load(scene), settings);
  EXPECT_TRUE(key.has_value()) << scene;
  return key.value_or("");
}

// Changes the byte at `offset` of `file` (inside its leading comment, so the
// scene still loads and looks the same).
void flip_byte(const fs::path& file, std::streamoff offset) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(offset);
  char c = 0;
  f.get(c);
  f.seekp(offset);
  f.put(c == 'x' ? 'y' : 'x');
}

TEST(BakeKey, ListsTheSceneFileMeshMaterialsAndTextures) {
  std::vector<std::string> names;
  for (const fs::path& f : scene_source_files(load(kTexturedFloor)))
    names.push_back(f.filename().string());
  for (const char* expected : {"scene.json", "textured-floor.obj", "textured-floor.mtl",
                               "checker.png", "fence-mask.png", "wall-ridges.png"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
}

TEST(BakeKey, StaysWhenTheSceneFolderIsCopiedElsewhere) {
  test::ScratchDir dir;
  const fs::path a = dir.path() / "a" / "textured-floor";
  const fs::path b = dir.path() / "deeper" / "other-name";
  fs::create_directories(a.parent_path());
  fs::create_directories(b.parent_path());
  fs::copy(kTexturedFloor, a, fs::copy_options::recursive);
  fs::copy(kTexturedFloor, b, fs::copy_options::recursive);
  const std::string key = key_of(kTexturedFloor);
  EXPECT_EQ(key.size(), 16u);
  EXPECT_EQ(key_of(a), key);
  EXPECT_EQ(key_of(b), key);
}

TEST(BakeKey, ChangesWithOneByteOfTheMeshOrItsMaterials) {
  const std::string key = key_of(kTexturedFloor);
  for (const char* file : {"textured-floor.obj", "textured-floor.mtl"}) {
    test::ScratchDir dir;
    const fs::path copy = dir.path() / "scene";
    fs::copy(kTexturedFloor, copy, fs::copy_options::recursive);
    flip_byte(copy / file, 10);
    EXPECT_NE(key_of(copy), key) << file;
  }
}

TEST(BakeKey, ChangesWithOneSettingOrDensityNotWithTheTemporaryFolder) {
  const Scene scene = load(kCornellBox);
  const BakeSettings base;
  const std::string key = *bake_key(scene, base);
  BakeSettings s = base;
  s.seed = 2;
  EXPECT_NE(*bake_key(scene, s), key);
  s = base;
  s.error_budget = 0.0200001;  // beyond the 6 digits settings print with
  EXPECT_NE(*bake_key(scene, s), key);
  s = base;
  s.dump_matrices = true;  // changes what the folder holds
  EXPECT_NE(*bake_key(scene, s), key);
  // The scene's own default, asked for explicitly: the same bake.
  s = base;
  s.voxel_resolution = 16;
  EXPECT_EQ(*bake_key(scene, s), key);
  s = base;
  s.out_of_core_dir = "/somewhere/else";
  EXPECT_EQ(*bake_key(scene, s), key);

  Scene denser = scene;
  denser.meshes.front().patch_density = 2.0f;
  EXPECT_NE(*bake_key(denser, base), key);
}

TEST(BakeKey, NoneForASceneNotReadFromFiles) {
  Scene scene = load(kCornellBox);
  scene.path.clear();
  EXPECT_FALSE(bake_key(scene, {}).has_value());
}

BakeSettings small_settings() {
  BakeSettings s;
  s.voxel_resolution = 3;
  s.transport.bounces = 2;
  s.transport.backend = TransportSettings::Backend::OpenBLAS;
  s.pictures = false;
  s.final_gather_rays = 16;
  s.closure_rays = 32;
  return s;
}

TEST(BakeKey, StoredOnlyForACompleteReadableBake) {
  test::ScratchDir dir;
  const Scene scene = load(kCornellBox);
  Diagnostics d;
  Progress quiet;
  const BakeResult r = Baker(scene, small_settings(), d).run(quiet);
  ASSERT_EQ(r.key, *bake_key(scene, small_settings()));
  const fs::path bake = dir.path() / "bake";
  write_bake(bake, scene, r, d);
  std::string why;
  EXPECT_EQ(stored_bake_key(bake, &why), r.key);
  EXPECT_EQ(why, "");

  EXPECT_FALSE(stored_bake_key(dir.path() / "nothing", &why).has_value());
  EXPECT_EQ(why, "");  // no folder: nothing to say

  fs::resize_file(bake / bake_file::kPatches, 100);  // a half-copied folder
  EXPECT_FALSE(stored_bake_key(bake, &why).has_value());
  EXPECT_NE(why.find("patches.npy"), std::string::npos) << why;

  std::ofstream(bake / bake_file::kManifest) << "{ not json";
  EXPECT_FALSE(stored_bake_key(bake, &why).has_value());
  EXPECT_NE(why.find("manifest.json"), std::string::npos) << why;

  std::ofstream(bake / bake_file::kManifest) << R"({"key": "0123456789abcdef", "files": 7})";
  EXPECT_FALSE(stored_bake_key(bake, &why).has_value());
  EXPECT_FALSE(why.empty());
}

TEST(BakeKey, ABakeIsKeyedByItsFilesAsLoadedNotAsEditedSince) {
  test::ScratchDir dir;
  const fs::path copy = dir.path() / "scene";
  fs::copy(kCornellBox, copy, fs::copy_options::recursive);
  const Scene scene = load(copy);
  const std::optional<std::string> content = scene_content_hash(scene);
  ASSERT_TRUE(content.has_value());
  flip_byte(copy / "CornellBox-Original.obj", 2);  // edited while the studio holds the scene
  Diagnostics d;
  Progress quiet;
  Baker baker(scene, small_settings(), d);
  baker.set_scene_content(content);
  const BakeResult r = baker.run(quiet);
  EXPECT_EQ(r.key, bake_key(*content, scene, small_settings()));
  EXPECT_NE(r.key, *bake_key(scene, small_settings())) << "keyed by the edited file";
}

TEST(BakerStageDone, EachStageInOrderWithItsResults) {
  const Scene scene = load(kCornellBox);
  Diagnostics d;
  Progress quiet;
  Baker baker(scene, small_settings(), d);
  std::vector<BakeStage> stages;
  std::size_t voxels = 0, samples = 0, patches = 0;
  baker.set_stage_done([&](BakeStage stage, const BakeResult& partial) {
    stages.push_back(stage);
    if (stage == BakeStage::Geometry) {
      voxels = partial.voxels.voxels.size();
      samples = partial.samples.samples.size();
      EXPECT_TRUE(partial.patches.patches.empty());
    }
    if (stage == BakeStage::Patches) patches = partial.patches.size();
  });
  const BakeResult r = baker.run(quiet);
  EXPECT_EQ(stages,
            (std::vector<BakeStage>{BakeStage::Geometry, BakeStage::Patches, BakeStage::FormFactors,
                                    BakeStage::Transport, BakeStage::Compress}));
  EXPECT_EQ(voxels, r.voxels.voxels.size());
  EXPECT_EQ(samples, r.samples.samples.size());
  EXPECT_GE(patches, r.patches.size());  // the checks prune patches that see nothing

  // The grid a front end shows first is the bake's.
  BakeSettings s = small_settings();
  s.apply_scene_defaults(scene.defaults);
  const Voxelization grid = Baker::voxel_grid(scene, s, nullptr);
  EXPECT_EQ(grid.voxels.size(), r.voxels.voxels.size());
  EXPECT_EQ(s.voxel_resolution, r.settings.voxel_resolution);
}

}  // namespace
}  // namespace bounce
