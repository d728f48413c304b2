// `bounce report --quick` on the Cornell box: the table has a row per swept
// setting, every error is finite and positive, and what the mathematics
// implies holds -- more bounces never carry less indirect light (T_K =
// sum_{k<=K} (rho F)^k is a sum of non-negative terms, so T_1 b <= T_2 b <=
// T_3 b <= T_inf b entry by entry, and auto stops at or before inf). The
// reference comes from the cache on the second run.
#include <cmath>
#include <map>
#include <set>

#include "cli_harness.h"

namespace bounce::itest {
namespace {

TEST(CliReport, QuickSweepOnTheCornellBox) {
  TempDir dir;
  const fs::path cache = dir / "cache";
  const RunResult r = run({"report", scene("cornell-box"), "--quick", "--out",
                           (dir / "report").string(), "--cache", cache.string(), "-q"},
                          dir.path(), 300.0);
  ASSERT_EQ(r.exit_code, 0) << r;
  ASSERT_TRUE(fs::exists(dir / "report" / "report.md"));
  const json report = parse_json(read_text(dir / "report" / "report.json"));

  // 2 modes x 2 patch counts x (bounces 1, 2, 3, auto, inf with dense, and
  // paper and ours at auto) = 28 rows, in the file and on stdout.
  const std::size_t rows = 2 * 2 * (5 + 2);
  ASSERT_EQ(report.at("rows").size(), rows);
  EXPECT_EQ(lines_starting_with(r.out, "| virtual |").size() +
                lines_starting_with(r.out, "| voxel |").size(),
            rows);
  EXPECT_EQ(lines_starting_with(read_text(dir / "report" / "report.md"), "| virtual |").size(),
            rows / 2);
  EXPECT_FALSE(report.at("reference").at("images_from_cache").get<bool>());

  std::map<std::string, std::map<std::string, double>> power;  // setting -> bounces -> T b power
  bool any_pareto = false;
  std::map<std::string, std::map<std::string, double>> layout;       // bake -> key -> error
  std::map<std::string, std::map<std::string, double>> probe_level;  // setting -> bounces -> level
  for (const json& row : report.at("rows")) {
    // The compression's own light error: none for the exact matrix, some
    // for the compressed ones.
    const double compression = row.at("compression_light_rel_rms_max").get<double>();
    if (row.at("codec_name") == "dense")
      EXPECT_EQ(compression, 0.0) << row.dump();
    else
      EXPECT_GT(compression, 0.0) << row.dump();
    for (const char* key : {"image_indirect_noise_corrected_relative_rmse",
                            "vertex_indirect_noise_corrected_relative_rmse"}) {
      const double e = row.at(key).get<double>();
      EXPECT_TRUE(std::isfinite(e) && e > 0.0) << key << " = " << e << " in " << row.dump();
    }
    for (const char* part : {"image_full", "image_indirect"}) {
      const json& m = row.at(part);
      for (const char* key : {"mse", "relative_rmse", "psnr", "ssim"})
        EXPECT_TRUE(std::isfinite(m.at(key).get<double>())) << part << "." << key;
      EXPECT_GT(m.at("mse").get<double>(), 0.0);
      EXPECT_LE(m.at("ssim").get<double>(), 1.0);
    }
    // The layout errors (exact patch values through the same gather): one
    // pair per bake, whatever the row's bounces and codec, and below the
    // 1-bounce row's error, which misses the light of every later bounce.
    const std::string bake_key =
        row.at("mode").get<std::string>() + std::to_string(row.at("patches").get<int>());
    for (const char* key : {"layout_image_indirect_noise_corrected_relative_rmse",
                            "layout_vertex_indirect_noise_corrected_relative_rmse"}) {
      // 0 when it is below the reference's noise (the quick reference is
      // noisy, and the Cornell box's picture through the gather's seen
      // weights gets there).
      const double e = row.at(key).get<double>();
      EXPECT_TRUE(std::isfinite(e) && e >= 0.0) << key << " = " << e << " in " << row.dump();
      const auto [it, first] = layout[bake_key].emplace(key, e);
      EXPECT_EQ(it->second, e) << key << " differs between rows of bake " << bake_key;
    }
    if (row.at("bounces") == "1") {
      EXPECT_GT(row.at("image_indirect_noise_corrected_relative_rmse").get<double>(),
                row.at("layout_image_indirect_noise_corrected_relative_rmse").get<double>())
          << row.dump();
    }
    EXPECT_GT(row.at("bake_seconds").get<double>(), 0.0);
    EXPECT_GT(row.at("update_ms").get<double>(), 0.0);
    EXPECT_GT(row.at("matrix_bytes").get<std::size_t>(), 0u);
    any_pareto = any_pareto || row.at("pareto").get<bool>();
    // The light probes' column: measured on every row; a grid with no probe
    // gives every point nothing, which is all of the reference's light.
    const double probe_error = row.at("probe_noise_corrected_relative_rmse").get<double>();
    EXPECT_TRUE(std::isfinite(probe_error) && probe_error >= 0.0) << row.dump();
    if (row.at("probes").get<std::size_t>() > 0)
      EXPECT_GT(row.at("probe_level").get<double>(), 0.0) << row.dump();
    else
      EXPECT_NEAR(probe_error, 1.0, 1e-9) << row.dump();
    if (row.at("codec") == "dense") {
      const std::string setting =
          row.at("mode").get<std::string>() + std::to_string(row.at("patches").get<int>());
      power[setting][row.at("bounces").get<std::string>()] = row.at("indirect_power").get<double>();
      if (row.at("probes").get<std::size_t>() > 0)
        probe_level[setting][row.at("bounces").get<std::string>()] =
            row.at("probe_level").get<double>();
    }
  }
  EXPECT_GT(report.at("reference").at("probe_points").get<std::size_t>(), 0u);
  // The probes hold light reflected at least once: more bounces, more light
  // at every probe, against the same reference.
  for (const auto& [setting, level] : probe_level)
    EXPECT_LT(level.at("1"), level.at("inf")) << setting;
  EXPECT_TRUE(any_pareto);
  ASSERT_EQ(power.size(), 4u);
  for (const auto& [setting, p] : power) {
    // float sums: a relative slack of 1e-5 for round-off only.
    const auto le = [](double a, double b) { return a <= b * (1.0 + 1e-5) + 1e-12; };
    EXPECT_GT(p.at("1"), 0.0) << setting;
    EXPECT_TRUE(le(p.at("1"), p.at("2"))) << setting;
    EXPECT_TRUE(le(p.at("2"), p.at("3"))) << setting;
    EXPECT_TRUE(le(p.at("3"), p.at("inf"))) << setting;
    EXPECT_TRUE(le(p.at("auto"), p.at("inf"))) << setting;
    EXPECT_LT(p.at("1"), p.at("inf")) << setting << ": a second bounce must add light";
  }

  // Second run, one row: the reference is read back from the cache.
  const RunResult again =
      run({"report", scene("cornell-box"), "--quick", "--modes", "virtual", "--patches", "60",
           "--bounces", "inf", "--codecs", "dense", "--json", "--no-light-probes", "--out",
           (dir / "again").string(), "--cache", cache.string()},
          dir.path(), 120.0);
  ASSERT_EQ(again.exit_code, 0) << again;
  const json second = parse_json(again.out);
  EXPECT_TRUE(second.at("reference").at("images_from_cache").get<bool>());
  EXPECT_TRUE(second.at("reference").at("vertices_from_cache").get<bool>());
  EXPECT_EQ(second.at("reference").at("noise_floor_indirect_relative_rmse"),
            report.at("reference").at("noise_floor_indirect_relative_rmse"));
  EXPECT_EQ(second.at("rows").size(), 1u);
  // Without the probes' column.
  EXPECT_EQ(second.at("reference").at("probe_points").get<std::size_t>(), 0u);
  EXPECT_EQ(second.at("rows").at(0).at("probe_level").get<double>(), 0.0);
}

TEST(CliReport, BakeWithReferencePrintsItsErrorAndRunTime) {
  TempDir dir;
  RunOptions o;
  o.cwd = dir.path();
  o.env["XDG_CACHE_HOME"] = (dir / "xdg").string();  // not the user's cache
  o.timeout = std::chrono::duration<double>(120.0);
  const RunResult r = run({"bake", scene("cornell-box"), "--voxel", "4", "--out",
                           (dir / "bake").string(), "--reference", "--json", "-q"},
                          o);
  ASSERT_EQ(r.exit_code, 0) << r;
  const json check = parse_json(r.out).at("reference_check");
  const double error = check.at("indirect_relative_rmse").get<double>();
  EXPECT_TRUE(std::isfinite(error) && error >= 0.0) << check.dump();
  EXPECT_GT(check.at("reference_noise").get<double>(), 0.0);
  EXPECT_GT(check.at("update_ms").get<double>(), 0.0);
  // The light move includes the gather to the lit mesh's vertices.
  EXPECT_GT(check.at("gather_vertices").get<std::size_t>(), 0u);
  EXPECT_GT(check.at("gather_ms").get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(check.at("light_move_ms").get<double>(),
                   check.at("update_ms").get<double>() + check.at("gather_ms").get<double>());
  EXPECT_FALSE(check.at("reference_cached").get<bool>());
  // The reference landed in $XDG_CACHE_HOME/bounce/reference.
  EXPECT_FALSE(fs::is_empty(dir / "xdg" / "bounce" / "reference"));
}

TEST(CliReport, BadSweepValuesNameTheOption) {
  TempDir dir;
  const RunResult r = run({"report", scene("cornell-box"), "--quick", "--bounces", "0", "--out",
                           (dir / "r").string(), "--no-cache"},
                          dir.path());
  EXPECT_EQ(r.exit_code, 1) << r;
  EXPECT_TRUE(contains(r.err, "--bounces")) << r;
  const RunResult c = run({"report", scene("cornell-box"), "--quick", "--codecs", "zip", "--out",
                           (dir / "r").string(), "--no-cache"},
                          dir.path());
  EXPECT_EQ(c.exit_code, 1) << c;
  EXPECT_TRUE(contains(c.err, "--codecs")) << c;
  EXPECT_FALSE(fs::exists(dir / "r" / "report.json"));
}

}  // namespace
}  // namespace bounce::itest
