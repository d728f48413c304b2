// `bounce info` and the --help of every command.
#include "cli_harness.h"

namespace bounce::itest {
namespace {

TEST(Info, CornellBoxJsonReportsItsTrianglesAndMaterials) {
  TempDir tmp;
  const RunResult r = run({"info", scene("cornell-box"), "--json"}, tmp.path());
  ASSERT_EQ(r.exit_code, 0) << r;
  const json j = parse_json(r.out);
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j["name"], "cornell-box");
  // 36 triangles in the OBJ, of which 4 repeat faces already there and are
  // skipped with a warning each.
  EXPECT_EQ(j["triangles"], 32) << j.dump(2);
  EXPECT_EQ(j["materials"].size(), 8u) << j["materials"].dump(2);
  std::size_t duplicate_warnings = 0;
  for (const json& w : j["warnings"])
    duplicate_warnings += contains(w.get<std::string>(), "duplicate") ? 1 : 0;
  EXPECT_GE(duplicate_warnings, 1u) << j["warnings"].dump(2);
  // The ceiling light is the one emissive material (two triangles).
  EXPECT_EQ(j["emissive_triangles"], 2);
  std::size_t triangles_in_meshes = 0;
  for (const json& m : j["meshes"]) triangles_in_meshes += m["triangles"].get<std::size_t>();
  EXPECT_EQ(triangles_in_meshes, 32u);
  EXPECT_TRUE(lines_starting_with(r.err, "bounce: error").empty()) << r;
  EXPECT_EQ(entries(tmp.path()), std::vector<std::string>{}) << "info wrote files";
}

// What the samples' albedo comes from beyond the flat material colours:
// textured triangles and per-vertex colours, in the text and the JSON.
TEST(Info, SaysWhetherTheSceneHasTexturesAndVertexColours) {
  TempDir tmp;
  const RunResult plain = run({"info", scene("cornell-box")}, tmp.path());
  ASSERT_EQ(plain.exit_code, 0) << plain;
  EXPECT_TRUE(contains(plain.out, "  surface     0 of 32 triangles textured, no vertex colours\n"))
      << plain.out;
  const json plain_json = parse_json(run({"info", scene("cornell-box"), "--json"}, tmp.path()).out);
  EXPECT_EQ(plain_json["vertex_colours"], false) << plain_json.dump(2);
  EXPECT_EQ(plain_json["textured_triangles"], 0) << plain_json.dump(2);

  // Of its 6 triangles the floor's two carry the checker; the wall's normal
  // map and the fence's alpha mask are no albedo textures.
  const json textured =
      parse_json(run({"info", scene("textured-floor"), "--json"}, tmp.path()).out);
  EXPECT_EQ(textured["textured_triangles"], 2) << textured.dump(2);
  EXPECT_EQ(textured["vertex_colours"], false) << textured.dump(2);

  // One triangle with 8-bit PLY colours.
  const fs::path ply = tmp / "coloured.ply";
  write_text(ply,
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
             "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
             "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
             "0 0 0 255 0 128\n1 0 0 0 255 64\n0 1 0 128 32 255\n3 0 1 2\n");
  const RunResult coloured = run({"info", ply.string()}, tmp.path());
  ASSERT_EQ(coloured.exit_code, 0) << coloured;
  EXPECT_TRUE(contains(coloured.out, "  surface     0 of 1 triangles textured, vertex colours\n"))
      << coloured.out;
  const json coloured_json = parse_json(run({"info", ply.string(), "--json"}, tmp.path()).out);
  EXPECT_EQ(coloured_json["vertex_colours"], true) << coloured_json.dump(2);
}

TEST(Info, MissingSceneIsOneError) {
  TempDir tmp;
  const std::string missing = (tmp / "nothing-here").string();
  const RunResult r = run({"info", missing, "--json"}, tmp.path());
  EXPECT_EQ(r.exit_code, 1) << r;
  const auto errors = lines_starting_with(r.err, "bounce: error: ");
  ASSERT_EQ(errors.size(), 1u) << r;
  EXPECT_TRUE(contains(errors[0], missing)) << errors[0];
  EXPECT_TRUE(r.out.empty()) << r;
}

struct HelpCase {
  std::vector<std::string> command;
  std::vector<std::string> mentions;
  std::vector<std::string> must_not_mention;
};

void PrintTo(const HelpCase& c, std::ostream* os) { *os << testing::PrintToString(c.command); }

class Help : public ::testing::TestWithParam<HelpCase> {};

TEST_P(Help, ExitsZeroWithUsageAndOptions) {
  const HelpCase& c = GetParam();
  TempDir tmp;
  std::vector<std::string> args = c.command;
  args.push_back("--help");
  const RunResult r = run(args, tmp.path());
  EXPECT_EQ(r.exit_code, 0) << r;
  EXPECT_TRUE(contains(r.out, "Usage:")) << r;
  for (const std::string& m : c.mentions)
    EXPECT_TRUE(contains(r.out, m)) << "help does not mention " << m << ":\n" << r.out;
  for (const std::string& m : c.must_not_mention)
    EXPECT_FALSE(contains(r.out, m)) << "help mentions " << m << ":\n" << r.out;
}

INSTANTIATE_TEST_SUITE_P(
    Commands, Help,
    ::testing::Values(HelpCase{{}, {"bounce", "bake", "info", "bench", "--version"}, {}},
                      HelpCase{
                          {"bake"},
                          {"scenes", "--out", "--voxel", "--patches-total", "--patches-per-voxel",
                           "--patches", "--samples-per-face", "--visibility-rays", "--seed",
                           "--dump-matrices", "--json", "--quiet"},
                          {}},
                      HelpCase{{"info"}, {"scene", "--json"}, {"--voxel"}},
                      // bench writes nothing: no --out folder (--out-of-core is a setting of
                      // the bake it times), no --dump-matrices.
                      HelpCase{{"bench", "bake"},
                               {"scenes", "--voxel", "--patches-total", "--patches-per-voxel",
                                "--patches", "--samples-per-face", "--visibility-rays", "--seed",
                                "--json", "--scaling", "--out-of-core"},
                               {"--out TEXT", "--dump-matrices"}}),
    [](const ::testing::TestParamInfo<HelpCase>& p) {
      std::string name;
      for (const std::string& c : p.param.command) name += (name.empty() ? "" : "_") + c;
      return name.empty() ? std::string("bounce") : name;
    });

TEST(CommandLine, NoSubcommandIsAnErrorNotACrash) {
  TempDir tmp;
  const RunResult r = run({}, tmp.path());
  EXPECT_NE(r.exit_code, 0) << r;
  EXPECT_LT(r.exit_code, 128) << r;
  EXPECT_FALSE(r.err.empty()) << r;
}

TEST(CommandLine, UnknownSubcommandIsAnError) {
  TempDir tmp;
  const RunResult r = run({"frobnicate"}, tmp.path());
  EXPECT_NE(r.exit_code, 0) << r;
  EXPECT_LT(r.exit_code, 128) << r;
  EXPECT_FALSE(r.err.empty()) << r;
}

}  // namespace
}  // namespace bounce::itest
