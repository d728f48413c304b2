// `bounce report --scene A --scene B`: one report folder per scene, and one
// table comparing them whose rows are each scene's own report.json rows; a
// scene that cannot be read is named and the others are still reported.
#include <cmath>

#include "cli_harness.h"

namespace bounce::itest {
namespace {

// The smallest sweep that still has a compressed row: one patch count, one
// mode, auto bounces, dense and ours, a coarse reference.
std::vector<std::string> tiny_sweep(const fs::path& dir) {
  return {"--quick",
          "--modes",
          "virtual",
          "--patches",
          "40",
          "--bounces",
          "auto",
          "--codecs",
          "dense",
          "ours",
          "--reference-samples",
          "16",
          "--width",
          "32",
          "--height",
          "24",
          "--no-plots",
          "--cache",
          (dir / "cache").string(),
          "-q"};
}

TEST(CliReportBatch, OneComparisonTableOfEveryScenesRows) {
  TempDir dir;
  std::vector<std::string> args = {"report",
                                   "--scene",
                                   scene("cornell-box"),
                                   "--scene",
                                   scene("furnace"),
                                   "--scene",
                                   (dir / "missing").string(),
                                   "--out",
                                   (dir / "r").string()};
  for (const std::string& a : tiny_sweep(dir.path())) args.push_back(a);
  const RunResult r = run(args, dir.path(), 120.0);
  // One scene of three failed: exit 2, its error names it.
  EXPECT_EQ(r.exit_code, 2) << r;
  EXPECT_TRUE(contains(r.err, (dir / "missing").string())) << r;
  const json comparison = parse_json(read_text(dir / "r" / "comparison.json"));
  EXPECT_EQ(comparison.at("failed").get<int>(), 1);
  const json& scenes = comparison.at("scenes");
  ASSERT_EQ(scenes.size(), 3u);
  EXPECT_FALSE(scenes[2].at("ok").get<bool>());
  std::size_t table_rows = 0;
  for (std::size_t k = 0; k < 2; ++k) {
    const json& s = scenes[k];
    ASSERT_TRUE(s.at("ok").get<bool>()) << s.dump();
    // The scene's own report, written beside the comparison.
    const json own =
        parse_json(read_text(fs::path(s.at("out").get<std::string>()) / "report.json"));
    const json& rows = s.at("rows");
    ASSERT_EQ(rows.size(), own.at("rows").size());
    ASSERT_EQ(rows.size(), 2u) << "dense and ours";
    bool any_pareto = false, compressed = false;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const json& a = rows[i];
      const json& b = own.at("rows")[i];
      EXPECT_EQ(a.at("patches"), b.at("patches"));
      EXPECT_EQ(a.at("codec"), b.at("codec"));
      EXPECT_EQ(a.at("update_ms"), b.at("update_ms"));
      EXPECT_EQ(a.at("compression_light_rel_rms_max"), b.at("compression_light_rel_rms_max"));
      EXPECT_EQ(a.at("image_indirect_noise_corrected_relative_rmse"),
                b.at("image_indirect_noise_corrected_relative_rmse"));
      EXPECT_EQ(a.at("pareto"), b.at("pareto"));
      any_pareto = any_pareto || a.at("pareto").get<bool>();
      compressed = compressed || a.at("compression_light_rel_rms_max").get<double>() > 0.0;
    }
    EXPECT_TRUE(any_pareto) << "a scene's fastest or most accurate row is on its front";
    EXPECT_TRUE(compressed) << "ours has a light error, dense none";
    const std::string name = s.at("name").get<std::string>();
    const std::size_t printed = lines_starting_with(r.out, "| " + name + " |").size();
    EXPECT_EQ(printed, rows.size()) << r.out;
    table_rows += printed;
  }
  EXPECT_NE(scenes[0].at("name"), scenes[1].at("name"));
  EXPECT_EQ(lines_starting_with(read_text(dir / "r" / "comparison.md"), "| cornell").size() +
                lines_starting_with(read_text(dir / "r" / "comparison.md"), "| furnace").size(),
            table_rows);
}

TEST(CliReportBatch, EverySceneFailingIsExitOneAndHelpNamesTheOption) {
  TempDir dir;
  std::vector<std::string> args = {
      "report", "--scene",           (dir / "a").string(), (dir / "b").string(),
      "--out",  (dir / "r").string()};
  for (const std::string& a : tiny_sweep(dir.path())) args.push_back(a);
  const RunResult r = run(args, dir.path(), 60.0);
  EXPECT_EQ(r.exit_code, 1) << r;
  EXPECT_TRUE(contains(r.err, (dir / "a").string()) && contains(r.err, (dir / "b").string())) << r;
  const RunResult help = run({"report", "--help"}, dir.path());
  EXPECT_EQ(help.exit_code, 0) << help;
  EXPECT_TRUE(contains(help.out, "--scene")) << help;
  EXPECT_TRUE(contains(help.out, "comparison.md")) << help;
  const RunResult none = run({"report", "--quick"}, dir.path());
  EXPECT_EQ(none.exit_code, 1) << none;
  EXPECT_TRUE(contains(none.err, "no scene")) << none;
}

}  // namespace
}  // namespace bounce::itest
