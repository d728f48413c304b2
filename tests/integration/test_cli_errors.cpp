// Bad input to `bounce bake`: each case exits 1 with exactly one
// `bounce: error: <file>: <what>` line and leaves no bake folder and no hidden
// temporary folder behind; repairable problems only warn and still bake.
#include <regex>

#include "cli_harness.h"

namespace bounce::itest {
namespace {

// Two parallel unit squares facing each other (they see each other, so the
// bake succeeds), plus `extra` OBJ lines. Vertices 1-4: bottom, 5-8: top.
std::string two_squares_obj(const std::string& extra = "") {
  return "mtllib squares.mtl\n"
         "o bottom\n"
         "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
         "usemtl grey\n"
         "f 1 2 3\nf 1 3 4\n"
         "o top\n"
         "v 0 0 1\nv 0 1 1\nv 1 1 1\nv 1 0 1\n"
         "usemtl grey\n"
         "f 5 6 7\nf 5 7 8\n" +
         extra;
}

constexpr const char* kMtl = "newmtl grey\nKd 0.5 0.5 0.5\n";
constexpr const char* kLight = R"("lights": [{"name": "mid", "position": [0.5, 0.5, 0.5]}])";

// Writes <dir>/scene.json (+ squares.obj, squares.mtl) and returns the folder.
fs::path write_scene(const fs::path& dir, const std::string& scene_json,
                     const std::string& obj = two_squares_obj()) {
  write_text(dir / "scene.json", scene_json);
  write_text(dir / "squares.obj", obj);
  write_text(dir / "squares.mtl", kMtl);
  return dir;
}

std::string default_scene_json() {
  return std::string(R"({"meshes": [{"file": "squares.obj"}], )") + kLight + "}\n";
}

class BakeErrors : public ::testing::Test {
 protected:
  TempDir tmp;
  fs::path out = tmp / "out";

  // The common contract of a fatal error: exit 1, exactly one error line
  // holding every `needles` string, no bake folder, no hidden leftovers.
  void expect_fatal(const RunResult& r, const std::vector<std::string>& needles) {
    EXPECT_EQ(r.exit_code, 1) << r;
    const auto errors = lines_starting_with(r.err, "bounce: error: ");
    ASSERT_EQ(errors.size(), 1u) << r;
    for (const std::string& n : needles)
      EXPECT_TRUE(contains(errors[0], n)) << "error line lacks '" << n << "': " << errors[0];
    EXPECT_FALSE(contains(r.err, "internal error")) << r;
    EXPECT_FALSE(fs::exists(out)) << "a failed bake created " << out;
    EXPECT_TRUE(hidden_leftovers(out).empty())
        << "hidden temporary folders left: " << testing::PrintToString(hidden_leftovers(out));
  }
};

TEST_F(BakeErrors, MissingScenePathIsOneErrorNamingThePath) {
  const std::string missing = (tmp / "no-such-scene").string();
  const RunResult r = run({"bake", missing, "--out", out.string()}, tmp.path());
  expect_fatal(r, {missing, "no such file"});
}

TEST_F(BakeErrors, MalformedSceneJsonReportsLineAndColumn) {
  // Line 4 starts a second array element without the comma after line 3;
  // the parser stops at the '{' in column 5.
  const fs::path dir = write_scene(tmp / "broken",
                                   "{\n"
                                   "  \"meshes\": [\n"
                                   "    { \"file\": \"squares.obj\" }\n"
                                   "    { \"file\": \"squares.obj\" }\n"
                                   "  ]\n"
                                   "}\n");
  const RunResult r = run({"bake", dir.string(), "--out", out.string()}, tmp.path());
  expect_fatal(r, {(dir / "scene.json").string()});
  std::smatch m;
  const std::regex where(R"(scene\.json:(\d+):(\d+))");
  ASSERT_TRUE(std::regex_search(r.err, m, where)) << r;
  EXPECT_EQ(std::stoi(m[1].str()), 4) << "line of the missing comma: " << r.err;
  EXPECT_EQ(std::stoi(m[2].str()), 5) << "column of the unexpected '{': " << r.err;
}

TEST_F(BakeErrors, NanVertexIsOneErrorNamingTheMeshFile) {
  const fs::path dir =
      write_scene(tmp / "nan", default_scene_json(), two_squares_obj("v nan 0 0\nf 1 2 9\n"));
  const RunResult r = run({"bake", dir.string(), "--out", out.string()}, tmp.path());
  expect_fatal(r, {(dir / "squares.obj").string(), "NaN"});
}

TEST_F(BakeErrors, SceneOfOnlyZeroAreaTrianglesHasNoGeometryLeft) {
  // Two triangles, each with three distinct but collinear corners.
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 0 2 0\n"
      "f 1 2 3\nf 1 4 5\n";
  const fs::path dir = write_scene(tmp / "flat", default_scene_json(), obj);
  const RunResult r = run({"bake", dir.string(), "--out", out.string()}, tmp.path());
  expect_fatal(r, {(dir / "scene.json").string(), "no geometry"});
  EXPECT_TRUE(contains(r.err, "degenerate")) << "the skipped triangles are not reported:\n" << r;
}

TEST_F(BakeErrors, SomeZeroAreaTrianglesAreSkippedWithAWarning) {
  // Vertex 9 is the midpoint of the bottom square's edge 1-2: triangle 1 9 2
  // has three distinct collinear corners, so zero area.
  const fs::path dir =
      write_scene(tmp / "mixed", default_scene_json(), two_squares_obj("v 0.5 0 0\nf 1 9 2\n"));
  const RunResult r =
      run({"bake", dir.string(), "--voxel", "4", "--out", out.string()}, tmp.path());
  ASSERT_EQ(r.exit_code, 0) << r;
  const auto warnings = lines_starting_with(r.err, "bounce: warning: ");
  const bool warned = std::any_of(warnings.begin(), warnings.end(), [](const std::string& w) {
    return contains(w, "degenerate") && contains(w, "squares.obj");
  });
  EXPECT_TRUE(warned) << "no warning about the degenerate triangle:\n" << r;
  EXPECT_TRUE(lines_starting_with(r.err, "bounce: error").empty()) << r;
  const json m = read_manifest(out);
  EXPECT_EQ(m["counts"]["triangles"], 4) << "the two squares' 4 triangles, the degenerate one out";
  bool in_manifest = false;
  for (const json& w : m["warnings"])
    in_manifest = in_manifest || contains(w["message"].get<std::string>(), "degenerate");
  EXPECT_TRUE(in_manifest) << "manifest warnings: " << m["warnings"].dump();
}

TEST_F(BakeErrors, UnknownSceneKeysAreWarningsNotErrors) {
  const std::string scene_json = std::string(R"({"meshes": [{"file": "squares.obj", "colour": 1}],
                                 "shininess": 2, )") +
                                 kLight + "}\n";
  const fs::path dir = write_scene(tmp / "unknown", scene_json);
  const RunResult r =
      run({"bake", dir.string(), "--voxel", "4", "--out", out.string()}, tmp.path());
  ASSERT_EQ(r.exit_code, 0) << r;
  for (const std::string key : {"meshes[0].colour", "shininess"}) {
    const auto warnings = lines_starting_with(r.err, "bounce: warning: ");
    const bool warned = std::any_of(warnings.begin(), warnings.end(), [&](const std::string& w) {
      return contains(w, key) && contains(w, "unknown key");
    });
    EXPECT_TRUE(warned) << "no 'unknown key' warning naming " << key << ":\n" << r;
  }
  EXPECT_TRUE(fs::exists(out / "manifest.json"));
}

// Option values that the CLI refuses, and the option name stderr must show.
struct BadOption {
  std::string name;
  std::vector<std::string> args;
  std::string option;
  bool checked_by_bake;  // true: bounce's own validation (exit 1, one error line); false: CLI11
};

void PrintTo(const BadOption& b, std::ostream* os) { *os << testing::PrintToString(b.args); }

class BakeRejectsOption : public ::testing::TestWithParam<BadOption> {};

TEST_P(BakeRejectsOption, ExitsNonZeroNamingTheOptionAndWritesNothing) {
  const BadOption& bad = GetParam();
  TempDir tmp;
  const fs::path out = tmp / "out";
  std::vector<std::string> args{"bake", scene("parallel-squares"), "--out", out.string()};
  args.insert(args.end(), bad.args.begin(), bad.args.end());
  const RunResult r = run(args, tmp.path());
  EXPECT_NE(r.exit_code, 0) << r;
  EXPECT_LT(r.exit_code, 128) << "ended by a signal: " << r;
  EXPECT_TRUE(contains(r.err, bad.option)) << "stderr does not name " << bad.option << ":\n" << r;
  if (bad.checked_by_bake) {
    EXPECT_EQ(r.exit_code, 1) << r;
    const auto errors = lines_starting_with(r.err, "bounce: error: ");
    ASSERT_EQ(errors.size(), 1u) << r;
    EXPECT_TRUE(contains(errors[0], bad.option)) << errors[0];
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(hidden_leftovers(out).empty());
}

INSTANTIATE_TEST_SUITE_P(
    Values, BakeRejectsOption,
    ::testing::Values(
        BadOption{"voxel_0", {"--voxel", "0"}, "--voxel", true},
        BadOption{"voxel_negative", {"--voxel", "-3"}, "--voxel", true},
        BadOption{"patches_per_voxel_0", {"--patches-per-voxel", "0"}, "--patches-per-voxel", true},
        BadOption{"samples_per_face_0", {"--samples-per-face", "0"}, "--samples-per-face", true},
        BadOption{"visibility_rays_0", {"--visibility-rays", "0"}, "--visibility-rays", true},
        BadOption{"patches_total_0", {"--patches-total", "0"}, "--patches-total", true},
        BadOption{"voxel_not_a_number", {"--voxel", "abc"}, "--voxel", false},
        BadOption{"unknown_patch_mode", {"--patches", "bogus"}, "--patches", false},
        BadOption{"bounces_0", {"--bounces", "0"}, "--bounces", true},
        BadOption{"bounces_too_many", {"--bounces", "65"}, "--bounces", true},
        BadOption{"bounces_not_a_number", {"--bounces", "3x"}, "--bounces", true},
        BadOption{"kept_fraction_above_1", {"--kept-fraction", "1.5"}, "--kept-fraction", true},
        BadOption{"error_budget_0", {"--error-budget", "0"}, "--error-budget", true},
        BadOption{"error_budget_with_paper",
                  {"--codec", "paper", "--error-budget", "0.1"},
                  "--error-budget",
                  true},
        BadOption{"size_limit_0", {"--size-limit", "0"}, "--size-limit", true},
        BadOption{"size_limit_above_1", {"--size-limit", "1.5"}, "--size-limit", true},
        BadOption{"size_limit_with_paper",
                  {"--codec", "paper", "--size-limit", "0.25"},
                  "--size-limit",
                  true},
        BadOption{"kept_fraction_with_dense",
                  {"--codec", "dense", "--kept-fraction", "0.1"},
                  "--kept-fraction",
                  true},
        BadOption{"unknown_codec", {"--codec", "zip"}, "--codec", false},
        BadOption{"unknown_gemm", {"--gemm", "cublas"}, "--gemm", false},
        BadOption{"unknown_light_probes", {"--light-probes", "maybe"}, "--light-probes", false},
        BadOption{
            "probe_volume_short", {"--light-probe-volumes", "1,2"}, "--light-probe-volumes", true},
        BadOption{"probe_volume_zero_spacing",
                  {"--light-probe-volumes", "0,0,0,1,1,1,0"},
                  "--light-probe-volumes",
                  true},
        BadOption{"probe_volume_outside",
                  {"--light-probe-volumes", "50,50,50,60,60,60,1"},
                  "--light-probe-volumes",
                  true},
        BadOption{"probe_volume_too_dense",
                  {"--light-probe-volumes", "0,0,0,1,1,1,0.00001"},
                  "--light-probe-volumes",
                  true},
        BadOption{
            "probe_volumes_without_volume", {"--light-probes", "volumes"}, "--light-probes", true},
        BadOption{"kept_fraction_and_error_budget",
                  {"--kept-fraction", "0.1", "--error-budget", "0.1"},
                  "--error-budget",
                  false},
        BadOption{"voxel_and_patches_total",
                  {"--voxel", "5", "--patches-total", "100"},
                  "--patches-total",
                  false}),
    [](const ::testing::TestParamInfo<BadOption>& p) { return p.param.name; });

TEST_F(BakeErrors, OutIntoNonEmptyFolderThatIsNotABakeIsRefusedAndUntouched) {
  write_text(out / "thesis.tex", "precious");
  write_text(out / "figures" / "plot.png", "also precious");
  const RunResult r =
      run({"bake", scene("parallel-squares"), "--voxel", "4", "--out", out.string()}, tmp.path());
  EXPECT_EQ(r.exit_code, 1) << r;
  const auto errors = lines_starting_with(r.err, "bounce: error: ");
  ASSERT_EQ(errors.size(), 1u) << r;
  EXPECT_TRUE(contains(errors[0], out.string())) << errors[0];
  EXPECT_TRUE(contains(errors[0], "not a bake")) << errors[0];
  EXPECT_EQ(entries(out), (std::vector<std::string>{"figures", "thesis.tex"}));
  EXPECT_EQ(entries(out / "figures"), std::vector<std::string>{"plot.png"});
  EXPECT_EQ(read_text(out / "thesis.tex"), "precious");
  EXPECT_EQ(read_text(out / "figures" / "plot.png"), "also precious");
  EXPECT_TRUE(hidden_leftovers(out).empty()) << testing::PrintToString(hidden_leftovers(out));
}

TEST_F(BakeErrors, OutOntoAnExistingFileIsRefusedAndUntouched) {
  write_text(out, "not a folder");
  const RunResult r =
      run({"bake", scene("parallel-squares"), "--voxel", "4", "--out", out.string()}, tmp.path());
  EXPECT_EQ(r.exit_code, 1) << r;
  const auto errors = lines_starting_with(r.err, "bounce: error: ");
  ASSERT_EQ(errors.size(), 1u) << r;
  EXPECT_TRUE(contains(errors[0], out.string())) << errors[0];
  EXPECT_TRUE(fs::is_regular_file(out));
  EXPECT_EQ(read_text(out), "not a folder");
  EXPECT_TRUE(hidden_leftovers(out).empty());
}

}  // namespace
}  // namespace bounce::itest
