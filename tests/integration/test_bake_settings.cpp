// Each bake option changes the bake the way its help text says, and the same
// seed reproduces the same bytes.
#include <algorithm>
#include <map>

#include "cli_harness.h"

namespace bounce::itest {
namespace {

struct Bake {
  RunResult run;
  json manifest;
  fs::path dir;
  std::size_t patches() const { return manifest["counts"]["patches"].get<std::size_t>(); }
};

// Bakes `scene_path` with `options` into <tmp>/<name>.
Bake bake(const TempDir& tmp, const std::string& name, const std::string& scene_path,
          const std::vector<std::string>& options, RunOptions run_options = {}) {
  Bake b;
  b.dir = tmp / name;
  std::vector<std::string> args{"bake", scene_path, "--quiet", "--out", b.dir.string()};
  args.insert(args.end(), options.begin(), options.end());
  if (run_options.cwd.empty()) run_options.cwd = tmp.path();
  // A hang guard, not a speed check: the light-error budget's trial
  // compressions take tens of seconds when two tests share two cores.
  if (run_options.timeout == std::chrono::duration<double>(60.0))
    run_options.timeout = std::chrono::duration<double>(300.0);
  b.run = run(args, run_options);
  EXPECT_EQ(b.run.exit_code, 0) << b.run;
  if (b.run.exit_code == 0) b.manifest = read_manifest(b.dir);
  return b;
}

// Patches per voxel as patches.npy counts them, against voxels.npy's column.
std::vector<std::size_t> patches_per_voxel(const Bake& b) {
  const auto p = read_npy_f32(b.dir / "patches.npy");
  const auto v = read_npy_f32(b.dir / "voxels.npy");
  std::vector<std::size_t> count(v.shape[0], 0);
  for (std::size_t i = 0; i < p.shape[0]; ++i)
    count.at(static_cast<std::size_t>(at(p, i, patch_col::kVoxel)))++;
  for (std::size_t k = 0; k < v.shape[0]; ++k)
    EXPECT_EQ(static_cast<float>(count[k]), at(v, k, voxel_col::kPatches)) << "voxel " << k;
  return count;
}

TEST(BakeSettings, FinerVoxelGridGivesMorePatches) {
  TempDir tmp;
  // Dense: the patches are what is compared, not the compression.
  const Bake coarse = bake(tmp, "v6", scene("cornell-box"), {"--voxel", "6", "--codec", "dense"});
  const Bake fine = bake(tmp, "v10", scene("cornell-box"), {"--voxel", "10", "--codec", "dense"});
  ASSERT_FALSE(coarse.manifest.is_null());
  ASSERT_FALSE(fine.manifest.is_null());
  EXPECT_LT(coarse.patches(), fine.patches());
  EXPECT_LT(coarse.manifest["counts"]["occupied_voxels"],
            fine.manifest["counts"]["occupied_voxels"]);
  // The resolution counts cells along the longest axis.
  for (const Bake* b : {&coarse, &fine}) {
    const int res = b->manifest["settings"]["resolved"]["voxel_resolution"].get<int>();
    const json& dims = b->manifest["grid"]["dims"];
    EXPECT_EQ(std::max({dims[0].get<int>(), dims[1].get<int>(), dims[2].get<int>()}), res);
    EXPECT_EQ(read_npy_f32(b->dir / "patches.npy").shape[0], b->patches());
  }
  EXPECT_EQ(coarse.manifest["settings"]["resolved"]["voxel_resolution"], 6);
  EXPECT_EQ(fine.manifest["settings"]["resolved"]["voxel_resolution"], 10);
}

TEST(BakeSettings, PatchesPerVoxelCapsThePatchesInEachVoxel) {
  TempDir tmp;
  const Bake one =
      bake(tmp, "k1", scene("cornell-box"), {"--voxel", "6", "--patches-per-voxel", "1"});
  const Bake three =
      bake(tmp, "k3", scene("cornell-box"), {"--voxel", "6", "--patches-per-voxel", "3"});
  ASSERT_FALSE(one.manifest.is_null());
  ASSERT_FALSE(three.manifest.is_null());
  EXPECT_LT(one.patches(), three.patches());
  EXPECT_EQ(one.manifest["counts"]["occupied_voxels"], three.manifest["counts"]["occupied_voxels"]);
  for (const auto& [b, cap] : {std::pair{&one, 1u}, std::pair{&three, 3u}}) {
    const std::string what = "--patches-per-voxel " + std::to_string(cap);
    EXPECT_EQ(b->manifest["settings"]["resolved"]["patches_per_voxel"], cap);
    const auto p = read_npy_f32(b->dir / "patches.npy");
    expect_valid_patches(p, what);
    patches_per_voxel(*b);  // checks voxels.npy's patch counts
    // A voxel may keep more patches than asked only when the rest face more
    // than 90 degrees apart (two sides of a thin wall), one emits and the
    // other does not (the light under the ceiling), or its samples stand on
    // two sides of something (the floor beside a box and behind it). The
    // manifest counts those voxels; the last kind leaves patches less than
    // 90 degrees apart, in at most the voxels it counts as having them.
    std::map<std::size_t, std::vector<std::size_t>> of_voxel;
    for (std::size_t i = 0; i < p.shape[0]; ++i)
      of_voxel[static_cast<std::size_t>(at(p, i, patch_col::kVoxel))].push_back(i);
    std::size_t above = 0, facing_alike = 0;
    for (const auto& [voxel, members] : of_voxel) {
      if (members.size() <= cap) continue;
      ++above;
      bool alike = false;
      for (std::size_t a = 0; a < members.size(); ++a)
        for (std::size_t c = a + 1; c < members.size(); ++c) {
          const auto emits = [&](std::size_t i) {
            return at(p, i, patch_col::kEmission) + at(p, i, patch_col::kEmission + 1) +
                       at(p, i, patch_col::kEmission + 2) >
                   0.0f;
          };
          if (emits(members[a]) != emits(members[c])) continue;
          double dot = 0.0;
          for (std::size_t k = 0; k < 3; ++k)
            dot += at(p, members[a], patch_col::kNormal + k) *
                   at(p, members[c], patch_col::kNormal + k);
          alike = alike || dot >= 1e-4;
        }
      facing_alike += alike ? 1 : 0;
    }
    EXPECT_LE(facing_alike,
              b->manifest["clustering"]["voxels_with_separated_samples"].get<std::size_t>())
        << what;
    EXPECT_LE(above, b->manifest["clustering"]["voxels_above_target"].get<std::size_t>()) << what;
  }
}

struct ModeCase {
  std::string scene;
  std::string mode;
  std::vector<std::string> extra;
};

void PrintTo(const ModeCase& c, std::ostream* os) { *os << c.scene << " --patches " << c.mode; }

class PatchModes : public ::testing::TestWithParam<ModeCase> {};

TEST_P(PatchModes, ProduceValidPatches) {
  const ModeCase& c = GetParam();
  TempDir tmp;
  std::vector<std::string> options{"--voxel", "6", "--patches", c.mode};
  options.insert(options.end(), c.extra.begin(), c.extra.end());
  RunOptions o;
  o.timeout = std::chrono::seconds(180);
  const Bake b = bake(tmp, "bake", scene(c.scene), options, o);
  ASSERT_FALSE(b.manifest.is_null());
  EXPECT_EQ(b.manifest["settings"]["resolved"]["patch_mode"], c.mode);
  const auto p = read_npy_f32(b.dir / "patches.npy");
  EXPECT_EQ(p.shape[0], b.patches());
  expect_valid_patches(p, c.scene + " --patches " + c.mode);
  const auto per_voxel = patches_per_voxel(b);
  if (c.mode == "voxel") {
    // One patch per voxel and normal direction: at most the six axes.
    EXPECT_LE(*std::max_element(per_voxel.begin(), per_voxel.end()), 6u);
  }
  // Patches carry the sampled area (less that of the few patches left out
  // because they see nothing); every part of the surface is carried, by a
  // ray's sample or by one at the part's centre, so sampled is the surface.
  const json& sampling = b.manifest["sampling"];
  const double sampled = sampling["sampled_area"].get<double>();
  EXPECT_NEAR(sampled, sampling["surface_area"].get<double>(), 1e-3 * sampled);
  EXPECT_LE(sampling["centre_sampled_area"].get<double>(), sampled);
  const double area = column_sum(p, patch_col::kArea);
  EXPECT_LE(area, sampled * 1.001);
  EXPECT_GT(area, sampled * 0.9);
  EXPECT_EQ(b.manifest["checks"]["form_factors"]["non_finite"], 0);
}

// The bunny's form factors are slow (tens of seconds at the default sampling):
// one ray per voxel face and one visibility ray keep this test short.
const std::vector<std::string> kFastBunny{"--samples-per-face", "1", "--visibility-rays", "1"};

INSTANTIATE_TEST_SUITE_P(Scenes, PatchModes,
                         ::testing::Values(ModeCase{"cornell-box", "voxel", {}},
                                           ModeCase{"cornell-box", "virtual", {}},
                                           ModeCase{"cornell-bunny", "voxel", kFastBunny},
                                           ModeCase{"cornell-bunny", "virtual", kFastBunny}),
                         [](const ::testing::TestParamInfo<ModeCase>& p) {
                           std::string name = p.param.scene + "_" + p.param.mode;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(BakeSettings, PatchesTotalLandsNearTheTarget) {
  TempDir tmp;
  const Bake b = bake(tmp, "total", scene("cornell-box"), {"--patches-total", "600"});
  ASSERT_FALSE(b.manifest.is_null());
  EXPECT_EQ(b.manifest["settings"]["resolved"]["patches_total_target"], 600);
  EXPECT_GE(static_cast<double>(b.patches()), 600.0 / 1.6);
  EXPECT_LE(static_cast<double>(b.patches()), 600.0 * 1.6);
  EXPECT_EQ(read_npy_f32(b.dir / "patches.npy").shape[0], b.patches());
}

TEST(BakeSettings, PatchDensityInSceneJsonShowsPerMeshInTheManifest) {
  TempDir tmp;
  // Two equal unit squares facing each other, one file each, the bottom one
  // at four times the density.
  const fs::path dir = tmp / "scene";
  write_text(dir / "bottom.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
  write_text(dir / "top.obj", "v 0 0 1\nv 0 1 1\nv 1 1 1\nv 1 0 1\nf 1 2 3\nf 1 3 4\n");
  write_text(dir / "scene.json", R"({
  "meshes": [{ "file": "bottom.obj", "name": "bottom", "patch_density": 4 },
             { "file": "top.obj", "name": "top" }],
  "lights": [{ "position": [0.5, 0.5, 0.5] }]
})");
  const Bake b = bake(tmp, "dense", dir.string(),
                      {"--patches-total", "96", "--samples-per-face", "6", "--codec", "dense",
                       "--final-gather-rays", "0"});
  ASSERT_FALSE(b.manifest.is_null());
  const json& meshes = b.manifest["meshes"];
  ASSERT_EQ(meshes.size(), 2u) << meshes.dump();
  EXPECT_EQ(meshes[0]["name"], "bottom");
  EXPECT_EQ(meshes[0]["patch_density"], 4.0);
  EXPECT_EQ(meshes[1]["name"], "top");
  EXPECT_EQ(meshes[1]["patch_density"], 1.0);
  for (const json& m : meshes) EXPECT_NEAR(m["area"].get<double>(), 1.0, 1e-6) << m.dump();
  const auto dense = meshes[0]["patches"].get<std::size_t>();
  const auto other = meshes[1]["patches"].get<std::size_t>();
  EXPECT_EQ(dense + other, b.patches());
  // About 4x (exactly 4x up to rounding and the grid the target resolves to;
  // the unit test pins the ratio down).
  EXPECT_GE(dense, 3 * other) << meshes.dump();
  // The patches' own mesh column (11) agrees with the manifest's counts.
  const auto p = read_npy_f32(b.dir / "patches.npy");
  ASSERT_EQ(p.shape[0], b.patches());
  std::size_t on_bottom = 0;
  for (std::size_t i = 0; i < p.shape[0]; ++i) on_bottom += p.data[i * 15 + 11] == 0.0f ? 1 : 0;
  EXPECT_EQ(on_bottom, dense);
}

TEST(BakeSettings, SameSeedGivesIdenticalBytesWhateverTheThreadCount) {
  TempDir tmp;
  RunOptions one_thread, two_threads;
  one_thread.env["OMP_NUM_THREADS"] = "1";
  two_threads.env["OMP_NUM_THREADS"] = "2";
  const std::vector<std::string> options{"--voxel", "6", "--seed", "7", "--dump-matrices"};
  const Bake a = bake(tmp, "a", scene("cornell-box"), options, two_threads);
  const Bake b = bake(tmp, "b", scene("cornell-box"), options, one_thread);
  ASSERT_FALSE(a.manifest.is_null());
  ASSERT_FALSE(b.manifest.is_null());
  for (const std::string file : {"patches.npy", "samples.npy", "voxels.npy", "F.npy"})
    EXPECT_TRUE(read_text(a.dir / file) == read_text(b.dir / file))
        << file << " differs between two bakes with the same seed";
}

TEST(BakeSettings, DifferentSeedsGiveDifferentSamples) {
  TempDir tmp;
  const Bake a = bake(tmp, "seed1", scene("cornell-box"), {"--voxel", "6", "--seed", "1"});
  const Bake b = bake(tmp, "seed2", scene("cornell-box"), {"--voxel", "6", "--seed", "2"});
  ASSERT_FALSE(a.manifest.is_null());
  ASSERT_FALSE(b.manifest.is_null());
  EXPECT_EQ(a.manifest["settings"]["resolved"]["seed"], 1);
  EXPECT_EQ(b.manifest["settings"]["resolved"]["seed"], 2);
  EXPECT_FALSE(read_text(a.dir / "samples.npy") == read_text(b.dir / "samples.npy"))
      << "samples.npy is the same for seeds 1 and 2";
}

TEST(BakeSettings, SceneBakeDefaultsApplyUnlessTheCommandLineOverrides) {
  TempDir tmp;
  // The furnace cube with its own bake block.
  const fs::path dir = tmp / "scene";
  fs::create_directories(dir);
  for (const std::string f : {"furnace.obj", "furnace.mtl"})
    fs::copy_file(kScenes / "furnace" / f, dir / f);
  write_text(dir / "scene.json", R"({
  "meshes": [{ "file": "furnace.obj" }],
  "bake": { "voxel": 5, "patches_per_voxel": 1, "samples_per_face": 2 }
})");
  const Bake defaults = bake(tmp, "defaults", dir.string(), {});
  ASSERT_FALSE(defaults.manifest.is_null());
  const json& s = defaults.manifest["settings"]["resolved"];
  EXPECT_EQ(s["voxel_resolution"], 5) << s.dump();
  EXPECT_EQ(s["patches_per_voxel"], 1) << "scene.json bake.patches_per_voxel ignored: " << s.dump();
  EXPECT_EQ(s["samples_per_face"], 2) << "scene.json bake.samples_per_face ignored: " << s.dump();

  const Bake overridden =
      bake(tmp, "overridden", dir.string(),
           {"--voxel", "4", "--patches-per-voxel", "2", "--samples-per-face", "3"});
  ASSERT_FALSE(overridden.manifest.is_null());
  const json& o = overridden.manifest["settings"]["resolved"];
  EXPECT_EQ(o["voxel_resolution"], 4) << o.dump();
  EXPECT_EQ(o["patches_per_voxel"], 2) << o.dump();
  EXPECT_EQ(o["samples_per_face"], 3) << o.dump();
}

// Every setting's option lands in the manifest: settings.requested holds
// what the command line asked for (null: left to the scene or the codec),
// settings.resolved what the bake used. Two bakes, since some options
// exclude others; between them every option is given a value other than its
// default.
TEST(BakeSettings, EveryOptionRoundTripsIntoTheManifest) {
  TempDir tmp;
  const std::string matrices = (tmp / "matrices").string();
  fs::create_directories(matrices);
  const Bake a = bake(tmp, "a", scene("cornell-box"),
                      {"--voxel",
                       "3",
                       "--patches-per-voxel",
                       "2",
                       "--patches",
                       "voxel",
                       "--samples-per-face",
                       "3",
                       "--visibility-rays",
                       "4",
                       "--closure-rays",
                       "64",
                       "--final-gather-rays",
                       "16",
                       "--final-gather-near",
                       "0.5",
                       "--final-gather-near-min-rays",
                       "3",
                       "--final-gather-spots",
                       "1",
                       "--light-probes",
                       "on",
                       "--light-probe-volumes",
                       "-0.5,0.5,-0.5,0.5,1.5,0.5,0.5",
                       "--light-probes-max",
                       "5000",
                       "--seed",
                       "7",
                       "--bounces",
                       "3",
                       "--gemm",
                       "openblas",
                       "--out-of-core",
                       "off",
                       "--out-of-core-dir",
                       matrices,
                       "--codec",
                       "paper",
                       "--ordering",
                       "paper-1-pass",
                       "--kept-fraction",
                       "0.08",
                       "--dump-matrices",
                       "--no-pictures"});
  ASSERT_FALSE(a.manifest.is_null());
  const json asked_a = {{"voxel_resolution", 3},
                        {"patches_total_target", nullptr},
                        {"patches_per_voxel", 2},
                        {"patch_mode", "voxel"},
                        {"samples_per_face", 3},
                        {"visibility_rays", 4},
                        {"closure_rays", 64},
                        {"final_gather_rays", 16},
                        {"final_gather_near", 0.5},
                        {"final_gather_near_min_rays", 3},
                        {"final_gather_spots", 1},
                        {"light_probes", "on"},
                        {"light_probe_volumes", "-0.5,0.5,-0.5,0.5,1.5,0.5,0.5"},
                        {"light_probes_max", 5000},
                        {"seed", 7},
                        {"bounces", 3},
                        {"gemm", "openblas"},
                        {"out_of_core", "off"},
                        {"out_of_core_dir", matrices},
                        {"codec", "paper"},
                        {"ordering", "paper-1-pass"},
                        {"kept_fraction", 0.08},
                        {"error_budget", nullptr},
                        {"size_limit", nullptr},
                        {"dump_matrices", true},
                        {"pictures", false}};
  EXPECT_EQ(a.manifest["settings"]["requested"], asked_a) << a.manifest["settings"].dump(2);
  // Everything was given, so the bake used it as asked.
  EXPECT_EQ(a.manifest["settings"]["resolved"], asked_a) << a.manifest["settings"].dump(2);

  const Bake b = bake(tmp, "b", scene("cornell-box"),
                      {"--patches-total", "60", "--codec", "ours", "--error-budget", "0.1",
                       "--size-limit", "0.5", "--bounces", "inf", "--no-pictures"});
  ASSERT_FALSE(b.manifest.is_null());
  const json& asked_b = b.manifest["settings"]["requested"];
  const json& used_b = b.manifest["settings"]["resolved"];
  EXPECT_EQ(asked_b["voxel_resolution"], nullptr) << asked_b.dump(2);
  EXPECT_EQ(asked_b["patches_total_target"], 60);
  EXPECT_EQ(asked_b["patches_per_voxel"], nullptr);
  EXPECT_EQ(asked_b["samples_per_face"], nullptr);
  EXPECT_EQ(asked_b["patch_mode"], "virtual");
  EXPECT_EQ(asked_b["bounces"], "inf");
  EXPECT_EQ(asked_b["codec"], "ours");
  EXPECT_EQ(asked_b["ordering"], nullptr);
  EXPECT_EQ(asked_b["kept_fraction"], nullptr);
  EXPECT_EQ(asked_b["error_budget"], 0.1);
  EXPECT_EQ(asked_b["size_limit"], 0.5);
  EXPECT_EQ(asked_b["pictures"], false);
  // Resolved: the grid the patch target chose, the scene's bake block (3 per
  // voxel) and the built-in 4 x 4 rays per face, the codec's own ordering
  // and the kept fraction the budget found.
  // The grid's resolution is the cell count along its longest axis.
  const json& dims = b.manifest["grid"]["dims"];
  EXPECT_EQ(used_b["voxel_resolution"].get<int>(),
            std::max({dims[0].get<int>(), dims[1].get<int>(), dims[2].get<int>()}));
  EXPECT_GE(used_b["voxel_resolution"].get<int>(), 1) << used_b.dump(2);
  EXPECT_EQ(used_b["patches_total_target"], 60);
  EXPECT_EQ(used_b["patches_per_voxel"], 3);
  EXPECT_EQ(used_b["samples_per_face"], 4);
  EXPECT_EQ(used_b["bounces"], "inf");
  EXPECT_EQ(used_b["codec"], "ours");
  EXPECT_EQ(used_b["ordering"], "ours");
  EXPECT_EQ(used_b["kept_fraction"], b.manifest["compression"]["kept_fraction"]);
  EXPECT_GT(used_b["kept_fraction"].get<double>(), 0.0);
  EXPECT_EQ(used_b["error_budget"], 0.1);
  EXPECT_EQ(used_b["size_limit"], 0.5);
  for (const json* block : {&asked_b, &used_b}) EXPECT_EQ(block->size(), asked_a.size());
}

}  // namespace
}  // namespace bounce::itest
