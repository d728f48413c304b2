// Several scenes in one `bounce bake`: one sub-folder per scene, a failing
// scene does not stop the others, exit code 2 when any failed.
#include <set>

#include "cli_harness.h"

namespace bounce::itest {
namespace {

TEST(BakeBatch, BrokenSceneFailsAloneWithExitCode2AndASummaryTable) {
  TempDir tmp;
  const fs::path dir = tmp / "bakes";
  const std::string broken = (tmp / "no-such-scene").string();
  const RunResult r = run({"bake", scene("parallel-squares"), scene("furnace"), broken, "--voxel",
                           "4", "--quiet", "--out", dir.string()},
                          tmp.path());
  EXPECT_EQ(r.exit_code, 2) << r;
  for (const std::string name : {"parallel-squares", "furnace"}) {
    ASSERT_TRUE(fs::exists(dir / name / "manifest.json")) << name << " not baked:\n" << r;
    const json m = read_manifest(dir / name);
    EXPECT_EQ(m["scene"]["name"], name);
    EXPECT_EQ(m["settings"]["resolved"]["voxel_resolution"], 4);
    const auto patches = read_npy_f32(dir / name / "patches.npy");
    EXPECT_EQ(json(patches.shape[0]), m["counts"]["patches"]) << name;
  }
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"furnace", "parallel-squares"}))
      << "only the two good scenes, no partial or hidden folders";

  // The summary: one row per scene, the broken one FAILED with its error.
  const auto lines = lines_of(r.out);
  auto row = [&](const std::string& start) -> std::string {
    for (const std::string& l : lines)
      if (l.rfind(start, 0) == 0) return l;
    return "";
  };
  EXPECT_TRUE(contains(row("parallel-squares"), "ok")) << r.out;
  EXPECT_TRUE(contains(row("furnace"), "ok")) << r.out;
  EXPECT_TRUE(contains(row(broken), "FAILED")) << r.out;
  EXPECT_TRUE(contains(row(broken), "no such file")) << r.out;
  EXPECT_TRUE(contains(r.out, "2 of 3 scenes")) << r.out;
  const auto errors = lines_starting_with(r.err, "bounce: error: ");
  ASSERT_EQ(errors.size(), 1u) << r;
  EXPECT_TRUE(contains(errors[0], broken)) << errors[0];
}

TEST(BakeBatch, JsonSummaryCountsTheFailures) {
  TempDir tmp;
  const fs::path dir = tmp / "bakes";
  const std::string broken = (tmp / "missing" / "scene.json").string();
  const RunResult r = run(
      {"bake", broken, scene("parallel-squares"), "--voxel", "4", "--json", "--out", dir.string()},
      tmp.path());
  EXPECT_EQ(r.exit_code, 2) << r;
  const json j = parse_json(r.out);
  EXPECT_EQ(j["failed"], 1) << j.dump(2);
  ASSERT_EQ(j["scenes"].size(), 2u) << j.dump(2);
  EXPECT_EQ(j["scenes"][0]["ok"], false);
  EXPECT_EQ(j["scenes"][1]["ok"], true);
  EXPECT_EQ(j["scenes"][1]["scene"], "parallel-squares");
  EXPECT_TRUE(fs::exists(dir / "parallel-squares" / "manifest.json"));
}

TEST(BakeBatch, QuotedGlobBakesEveryMatchingScene) {
  TempDir tmp;
  const fs::path dir = tmp / "bakes";
  // Passed to bounce unexpanded (no shell): bounce expands it itself.
  const std::string pattern = (kScenes / "p*-squares").string();
  const RunResult r =
      run({"bake", pattern, "--voxel", "4", "--quiet", "--out", dir.string()}, tmp.path());
  EXPECT_EQ(r.exit_code, 0) << r;
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"parallel-squares", "perpendicular-squares"}));
  for (const std::string name : {"parallel-squares", "perpendicular-squares"}) {
    ASSERT_TRUE(fs::exists(dir / name / "manifest.json")) << name << ":\n" << r;
    EXPECT_EQ(read_manifest(dir / name)["scene"]["name"], name);
  }
  EXPECT_TRUE(contains(r.out, "2 of 2 scenes")) << r.out;
}

TEST(BakeBatch, EveryScenePrintedAsBakedHasItsOwnBakeFolder) {
  // Two different scenes that are both named "squares" (a bare mesh is named
  // after its file): one must not silently replace the other.
  TempDir tmp;
  for (const std::string kind : {"parallel", "perpendicular"}) {
    const fs::path from = kScenes / (kind + "-squares");
    fs::create_directories(tmp / kind);
    fs::copy_file(from / (kind + "-squares.obj"), tmp / kind / "squares.obj");
    fs::copy_file(from / (kind + "-squares.mtl"), tmp / kind / (kind + "-squares.mtl"));
  }
  const fs::path dir = tmp / "bakes";
  const RunResult r = run({"bake", (tmp / "parallel" / "squares.obj").string(),
                           (tmp / "perpendicular" / "squares.obj").string(), "--voxel", "4",
                           "--json", "--quiet", "--out", dir.string()},
                          tmp.path());
  const json j = parse_json(r.out);
  std::size_t reported_ok = 0;
  for (const json& s : j["scenes"]) reported_ok += s["ok"].get<bool>() ? 1 : 0;
  std::size_t bakes_on_disk = 0;
  std::set<std::string> sources;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (fs::exists(e.path() / "manifest.json")) {
        ++bakes_on_disk;
        sources.insert(read_manifest(e.path())["scene"]["path"].get<std::string>());
      }
  EXPECT_EQ(bakes_on_disk, reported_ok)
      << "scenes reported as baked: " << reported_ok << ", bake folders: " << bakes_on_disk
      << " (one overwrote the other)\n"
      << r;
  EXPECT_EQ(sources.size(), bakes_on_disk);
  EXPECT_EQ(r.exit_code, reported_ok == 2 ? 0 : 2) << r;
}

}  // namespace
}  // namespace bounce::itest
