// `bounce solve` on a bake with light probes writes probe_sh.npy: the
// probes' irradiance SH for its light setting (docs/bake-format.md, "Light
// probes"), the values LightingSession::probe_sh gives for the same lights.
// A bake without probes has no such file. A scene.json that asks for a
// probe volume only gets that volume's probes, reported in the manifest and
// in probe_volume.npy; the command line's --light-probes overrides it.
#include "cli_harness.h"
#include "relight/lighting_session.h"

namespace bounce::itest {
namespace {

TEST(SolveProbes, ProbeShIsTheSessionsForTheSameLight) {
  TempDir tmp;
  const fs::path bake = tmp / "bake";
  const RunResult baked =
      run({"bake", scene("cornell-box"), "--voxel", "6", "--codec", "dense", "--light-probes", "on",
           "--no-pictures", "--quiet", "--out", bake.string()},
          tmp.path(), 120.0);
  ASSERT_EQ(baked.exit_code, 0) << baked;
  const glm::vec3 moved(-0.4f, 1.5f, 0.2f);
  const RunResult solved =
      run({"solve", bake.string(), "--light", "ceiling-point:-0.4,1.5,0.2", "--no-images",
           "--no-mesh", "--quiet", "--out", (tmp / "solve").string()},
          tmp.path(), 120.0);
  ASSERT_EQ(solved.exit_code, 0) << solved;
  const NpyArray<float> written = read_npy_f32(tmp / "solve" / "probe_sh.npy");

  LightingSession session(bake);
  session.move_light("ceiling-point", moved);
  session.light();
  std::vector<glm::vec3> sh;
  session.probe_sh(sh);
  ASSERT_FALSE(sh.empty());
  ASSERT_EQ(written.shape, (std::vector<std::size_t>{sh.size() / kShCoefficients, 9, 3}));
  double largest = 0.0;
  for (const glm::vec3& c : sh)
    largest =
        std::max({largest, std::abs(double(c.x)), std::abs(double(c.y)), std::abs(double(c.z))});
  ASSERT_GT(largest, 0.0);
  // The same product in another process: equal to float rounding of sums
  // whose order may follow the thread count.
  for (std::size_t i = 0; i < sh.size(); ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(written.data[3 * i + static_cast<std::size_t>(c)], sh[i][c], 1e-5 * largest)
          << "probe " << i / kShCoefficients << " coefficient " << i % kShCoefficients;

  // Without probes: no file.
  const fs::path plain = tmp / "plain";
  ASSERT_EQ(run({"bake", scene("cornell-box"), "--voxel", "4", "--codec", "dense", "--light-probes",
                 "off", "--no-pictures", "--quiet", "--out", plain.string()},
                tmp.path(), 120.0)
                .exit_code,
            0);
  ASSERT_EQ(run({"solve", plain.string(), "--no-images", "--no-mesh", "--quiet", "--out",
                 (tmp / "plain-solve").string()},
                tmp.path(), 120.0)
                .exit_code,
            0);
  EXPECT_TRUE(fs::exists(tmp / "plain-solve" / "patch_light.npy"));
  EXPECT_FALSE(fs::exists(tmp / "plain-solve" / "probe_sh.npy"));
}

TEST(SceneProbeVolumes, TheScenesVolumeAloneUnlessTheCommandLineSaysOtherwise) {
  TempDir tmp;
  const fs::path box = tmp / "box";
  fs::create_directories(box);
  const fs::path source = scene("cornell-box");
  for (const char* f : {"CornellBox-Original.obj", "CornellBox-Original.mtl"})
    fs::copy_file(source / f, box / f);
  json scene_json = json::parse(read_text(source / "scene.json"));
  scene_json["bake"] = {
      {"voxel", 6},
      {"light_probes", "volumes"},
      {"light_probe_volumes",
       json::array({{{"min", {-0.5, 1.25, -0.5}}, {"max", {0.5, 1.75, 0.5}}, {"spacing", 0.5}}})}};
  std::ofstream(box / "scene.json") << scene_json.dump(2);

  const fs::path only = tmp / "volume-only";
  ASSERT_EQ(run({"bake", box.string(), "--codec", "dense", "--no-pictures", "--quiet", "--out",
                 only.string()},
                tmp.path(), 120.0)
                .exit_code,
            0);
  const json m = read_manifest(only);
  // 3 x 2 x 3 lattice points, all in open air above the boxes.
  EXPECT_EQ(m["light_probes"]["probes"], 18) << m["light_probes"].dump(2);
  EXPECT_EQ(m["light_probes"]["surfaces"]["placed"], false);
  EXPECT_EQ(m["light_probes"]["volumes"][0]["probes"], 18);
  EXPECT_EQ(m["light_probes"]["volumes"][0]["lattice"], json::array({3, 2, 3}));
  EXPECT_EQ(m["settings"]["requested"]["light_probes"], "auto");
  EXPECT_EQ(m["settings"]["resolved"]["light_probes"], "volumes");
  EXPECT_EQ(m["settings"]["resolved"]["light_probe_volumes"], "-0.5,1.25,-0.5,0.5,1.75,0.5,0.5");
  const NpyArray<float> volumes = read_npy_f32(only / "probe_volume.npy");
  EXPECT_EQ(volumes.shape, (std::vector<std::size_t>{1, 9}));
  EXPECT_EQ(read_npy_f32(only / "probe_position.npy").shape, (std::vector<std::size_t>{18, 3}));

  const fs::path both = tmp / "both";
  ASSERT_EQ(run({"bake", box.string(), "--codec", "dense", "--light-probes", "on", "--no-pictures",
                 "--quiet", "--out", both.string()},
                tmp.path(), 120.0)
                .exit_code,
            0);
  const json b = read_manifest(both);
  EXPECT_EQ(b["light_probes"]["surfaces"]["placed"], true);
  EXPECT_GT(b["light_probes"]["surfaces"]["probes"].get<int>(), 0);
  EXPECT_EQ(b["light_probes"]["probes"].get<int>(),
            b["light_probes"]["surfaces"]["probes"].get<int>() + 18);
}

}  // namespace
}  // namespace bounce::itest
