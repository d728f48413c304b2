// What a bake folder holds, checked against the white furnace (the closed
// unit cube seen from inside): analytic areas and closure, shapes in the
// manifest against the .npy files, and replacing a previous bake.
#include <set>

#include "cli_harness.h"

namespace bounce::itest {
namespace {

class FurnaceBake : public ::testing::Test {
 protected:
  // One bake shared by the tests of this suite (about a second).
  static void SetUpTestSuite() {
    tmp = new TempDir();
    out = tmp->path() / "furnace";
    result = new RunResult(run({"bake", scene("furnace"), "--voxel", "6", "--dump-matrices",
                                "--json", "--out", out.string()},
                               tmp->path()));
  }
  static void TearDownTestSuite() {
    delete result;
    delete tmp;
  }
  void SetUp() override {
    ASSERT_EQ(result->exit_code, 0) << *result;
    summary = parse_json(result->out);
    ASSERT_TRUE(summary.is_object());
    manifest = read_manifest(out);
  }

  static inline TempDir* tmp = nullptr;
  static inline fs::path out;
  static inline RunResult* result = nullptr;
  json summary, manifest;
};

TEST_F(FurnaceBake, JsonOnStdoutIsTheManifestWritten) {
  EXPECT_EQ(summary, manifest);
  EXPECT_EQ(manifest["format"], "bounce-bake");
  EXPECT_EQ(manifest["scene"]["name"], "furnace");
  EXPECT_EQ(manifest["settings"]["resolved"]["voxel_resolution"], 6);
  EXPECT_EQ(manifest["settings"]["resolved"]["dump_matrices"], true);
  // A cube: 6 cells along every axis.
  EXPECT_EQ(manifest["grid"]["dims"], json::array({6, 6, 6}));
  EXPECT_EQ(manifest["counts"]["grid_cells"], 216);
  EXPECT_EQ(manifest["counts"]["triangles"], 12);
}

TEST_F(FurnaceBake, ArrayShapesMatchTheManifestCounts) {
  const auto n = summary["counts"]["patches"].get<std::size_t>();
  const auto s = summary["counts"]["samples"].get<std::size_t>();
  const auto v = summary["counts"]["occupied_voxels"].get<std::size_t>();
  EXPECT_GT(n, 0u);
  EXPECT_EQ(read_npy_f32(out / "patches.npy").shape, (std::vector<std::size_t>{n, 15}));
  EXPECT_EQ(read_npy_f32(out / "F.npy").shape, (std::vector<std::size_t>{n, n}));
  EXPECT_EQ(read_npy_f32(out / "samples.npy").shape, (std::vector<std::size_t>{s, 13}));
  EXPECT_EQ(read_npy_f32(out / "voxels.npy").shape, (std::vector<std::size_t>{v, 9}));
  // The surface of a cube cut into 6^3 cells touches every cell but the
  // 4^3 inner ones.
  EXPECT_EQ(v, 216u - 64u);
}

TEST_F(FurnaceBake, ManifestFileListMatchesTheFilesOnDisk) {
  std::set<std::string> listed;
  for (const json& f : manifest["files"]) {
    const std::string name = f["name"].get<std::string>();
    listed.insert(name);
    ASSERT_TRUE(fs::exists(out / name)) << name;
    EXPECT_EQ(f["bytes"].get<std::uintmax_t>(), fs::file_size(out / name)) << name;
  }
  // The furnace's matrix is far under 1 MiB: stored dense, so no DDS, CSR or
  // error pictures.
  EXPECT_EQ(listed, (std::set<std::string>{"patches.npy",
                                           "voxels.npy",
                                           "samples.npy",
                                           "carried_polygons.npy",
                                           "carried_area.npy",
                                           "carried_vertices.npy",
                                           "closure.npy",
                                           "gather_first.npy",
                                           "gather_source.npy",
                                           "gather_weight.npy",
                                           "gather_cluster.npy",
                                           "gather_share.npy",
                                           "gather_seen_first.npy",
                                           "gather_seen_sample.npy",
                                           "gather_seen_weight.npy",
                                           "gather_near_position.npy",
                                           "gather_near_normal.npy",
                                           "gather_near_albedo.npy",
                                           "gather_near_patch.npy",
                                           "gather_spot_first.npy",
                                           "gather_spot_weight.npy",
                                           "probe_position.npy",
                                           "probe_gather_first.npy",
                                           "probe_gather_source.npy",
                                           "probe_gather_weight.npy",
                                           "probe_gather_cluster.npy",
                                           "probe_gather_share.npy",
                                           "probe_gather_seen_first.npy",
                                           "probe_gather_seen_sample.npy",
                                           "probe_gather_seen_weight.npy",
                                           "F.npy",
                                           "T.npy",
                                           "T.png",
                                           "lights_first_hit.npy"}));
  std::set<std::string> on_disk;
  for (const std::string& e : entries(out)) on_disk.insert(e);
  listed.insert("manifest.json");
  EXPECT_EQ(on_disk, listed) << "files in the bake folder the manifest does not list (or v.v.)";
  EXPECT_TRUE(hidden_leftovers(out).empty());
}

TEST_F(FurnaceBake, PatchesHaveUnitInwardNormalsAndCoverTheCubesArea) {
  const auto p = read_npy_f32(out / "patches.npy");
  expect_valid_patches(p, "furnace patches");
  // The inner surface of the unit cube: 6 faces of area 1.
  EXPECT_NEAR(column_sum(p, patch_col::kArea), 6.0, 0.06);
  std::size_t outside = 0, outward = 0;
  for (std::size_t i = 0; i < p.shape[0]; ++i) {
    double facing = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
      const float x = at(p, i, patch_col::kPos + k);
      outside += (x < -1e-3f || x > 1.0f + 1e-3f) ? 1 : 0;
      facing += (0.5 - x) * at(p, i, patch_col::kNormal + k);
    }
    outward += facing > 0.0 ? 0 : 1;
  }
  EXPECT_EQ(outside, 0u) << "patch positions outside the cube";
  EXPECT_EQ(outward, 0u) << "patch normals that do not face the cube's centre";
  // Albedo 0.5 and emission 1 everywhere (furnace.mtl).
  for (std::size_t i = 0; i < p.shape[0]; ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      ASSERT_FLOAT_EQ(at(p, i, patch_col::kAlbedo + k), 0.5f) << "patch " << i;
      ASSERT_FLOAT_EQ(at(p, i, patch_col::kEmission + k), 1.0f) << "patch " << i;
    }
}

TEST_F(FurnaceBake, VoxelsAndSamplesAddUpToThePatchesAndTheSurface) {
  const auto p = read_npy_f32(out / "patches.npy");
  const auto vx = read_npy_f32(out / "voxels.npy");
  const auto s = read_npy_f32(out / "samples.npy");
  const auto n = static_cast<double>(p.shape[0]);
  EXPECT_NEAR(column_sum(vx, voxel_col::kArea), 6.0, 0.06);
  EXPECT_NEAR(column_sum(s, sample_col::kArea), 6.0, 0.06);
  EXPECT_DOUBLE_EQ(column_sum(vx, voxel_col::kSamples), static_cast<double>(s.shape[0]));
  EXPECT_DOUBLE_EQ(column_sum(vx, voxel_col::kPatches), n);
  std::size_t bad_voxel = 0, bad_patch = 0;
  for (std::size_t i = 0; i < s.shape[0]; ++i) {
    const float v = at(s, i, sample_col::kVoxel), q = at(s, i, sample_col::kPatch);
    bad_voxel += (v < 0.0f || v >= static_cast<float>(vx.shape[0])) ? 1 : 0;
    bad_patch += (q < -1.0f || q >= static_cast<float>(n)) ? 1 : 0;
  }
  EXPECT_EQ(bad_voxel, 0u) << "samples.npy voxel indices out of range";
  EXPECT_EQ(bad_patch, 0u) << "samples.npy patch indices out of range";
  for (std::size_t i = 0; i < p.shape[0]; ++i) {
    const float v = at(p, i, patch_col::kVoxel);
    ASSERT_TRUE(v >= 0.0f && v < static_cast<float>(vx.shape[0])) << "patch " << i;
  }
}

TEST_F(FurnaceBake, FormFactorRowsOfTheClosedCubeSumToOne) {
  const auto f = read_npy_f32(out / "F.npy");
  const auto p = read_npy_f32(out / "patches.npy");
  const std::size_t n = f.shape[0];
  ASSERT_EQ(p.shape[0], n);
  std::size_t non_finite = 0, negative = 0, bad_rows = 0;
  std::string first_bad;
  double exchange = 0.0, unreciprocated = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double row = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const float v = f.data[i * n + j];
      non_finite += std::isfinite(v) ? 0 : 1;
      negative += v < 0.0f ? 1 : 0;
      row += v;
      const double ai = at(p, i, patch_col::kArea), aj = at(p, j, patch_col::kArea);
      exchange += ai * v;
      unreciprocated += std::abs(ai * v - aj * f.data[j * n + i]) / 2.0;
    }
    if (std::abs(row - 1.0) > 0.02) {
      if (bad_rows == 0) first_bad = "row " + std::to_string(i) + " sums to " + std::to_string(row);
      ++bad_rows;
    }
  }
  EXPECT_EQ(non_finite, 0u);
  EXPECT_EQ(negative, 0u);
  EXPECT_EQ(bad_rows, 0u) << "rows whose sum is off 1 by more than 0.02; first: " << first_bad;
  // A_i F_ij = A_j F_ji: the exchanged energy is symmetric.
  EXPECT_LT(unreciprocated / exchange, 0.02);
  EXPECT_EQ(manifest["checks"]["form_factors"]["non_finite"], 0);
}

TEST_F(FurnaceBake, LeftOutListNamesTheEmptyGridCells) {
  const auto v = manifest["counts"]["occupied_voxels"].get<std::size_t>();
  const std::string empty = std::to_string(216 - v);
  bool found = false;
  for (const json& e : manifest["left_out"]) {
    const std::string message = e["message"].get<std::string>();
    found = found || (contains(message, "empty") && contains(message, empty));
  }
  EXPECT_TRUE(found) << "no left_out entry saying " << empty
                     << " cells are empty: " << manifest["left_out"].dump(2);
}

TEST(BakeFolder, RebakingIntoTheSameOutReplacesThePreviousBake) {
  TempDir tmp;
  const fs::path out = tmp / "bake";
  const RunResult first = run({"bake", scene("furnace"), "--voxel", "4", "--dump-matrices",
                               "--quiet", "--out", out.string()},
                              tmp.path());
  ASSERT_EQ(first.exit_code, 0) << first;
  const json m1 = read_manifest(out);
  ASSERT_TRUE(fs::exists(out / "F.npy"));
  EXPECT_EQ(m1["settings"]["resolved"]["voxel_resolution"], 4);

  const RunResult second = run({"bake", scene("furnace"), "--voxel", "6", "--patches-per-voxel",
                                "1", "--quiet", "--out", out.string()},
                               tmp.path());
  ASSERT_EQ(second.exit_code, 0) << second;
  const json m2 = read_manifest(out);
  EXPECT_EQ(m2["settings"]["resolved"]["voxel_resolution"], 6);
  EXPECT_EQ(m2["settings"]["resolved"]["patches_per_voxel"], 1);
  EXPECT_EQ(m2["settings"]["resolved"]["dump_matrices"], false);
  EXPECT_NE(m2["counts"], m1["counts"]);
  EXPECT_EQ(json(read_npy_f32(out / "patches.npy").shape[0]), m2["counts"]["patches"]);
  EXPECT_FALSE(fs::exists(out / "F.npy")) << "a file of the previous bake survived";
  EXPECT_EQ(entries(tmp.path()), std::vector<std::string>{"bake"})
      << "hidden temporary or old folders left next to the bake";

  // The same folder named with a trailing slash is the same bake folder.
  const RunResult third =
      run({"bake", scene("furnace"), "--voxel", "5", "--quiet", "--out", out.string() + "/"},
          tmp.path());
  ASSERT_EQ(third.exit_code, 0) << third;
  EXPECT_EQ(read_manifest(out)["settings"]["resolved"]["voxel_resolution"], 5);
  EXPECT_EQ(entries(tmp.path()), std::vector<std::string>{"bake"});
  EXPECT_EQ(entries(out), (std::vector<std::string>{"T.npy",
                                                    "T.png",
                                                    "carried_area.npy",
                                                    "carried_polygons.npy",
                                                    "carried_vertices.npy",
                                                    "closure.npy",
                                                    "gather_cluster.npy",
                                                    "gather_first.npy",
                                                    "gather_near_albedo.npy",
                                                    "gather_near_normal.npy",
                                                    "gather_near_patch.npy",
                                                    "gather_near_position.npy",
                                                    "gather_seen_first.npy",
                                                    "gather_seen_sample.npy",
                                                    "gather_seen_weight.npy",
                                                    "gather_share.npy",
                                                    "gather_source.npy",
                                                    "gather_spot_first.npy",
                                                    "gather_spot_weight.npy",
                                                    "gather_weight.npy",
                                                    "lights_first_hit.npy",
                                                    "manifest.json",
                                                    "patches.npy",
                                                    "probe_gather_cluster.npy",
                                                    "probe_gather_first.npy",
                                                    "probe_gather_seen_first.npy",
                                                    "probe_gather_seen_sample.npy",
                                                    "probe_gather_seen_weight.npy",
                                                    "probe_gather_share.npy",
                                                    "probe_gather_source.npy",
                                                    "probe_gather_weight.npy",
                                                    "probe_position.npy",
                                                    "samples.npy",
                                                    "voxels.npy"}));
}

}  // namespace
}  // namespace bounce::itest
