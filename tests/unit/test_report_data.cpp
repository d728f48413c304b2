// The report's rows as data (core/report/report_data.h): the Pareto front
// on rows whose answer is known, the virtual-against-voxel pairing, the
// row -> bake settings mapping, and report.json written and read back.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "base/error.h"
#include "report/report_data.h"
#include "scratch_dir.h"

namespace bounce {
namespace {

ReportRow row(const char* mode, int target, double error, double ms, const char* bounces = "auto",
              const char* codec = "dense") {
  ReportRow r;
  r.mode = mode;
  r.patches_target = target;
  r.patches = static_cast<std::size_t>(target + 1);
  r.bounces = bounces;
  r.codec_name = codec;
  r.codec = codec;
  r.indirect_error = error;
  r.direct_ms = ms;
  return r;
}

TEST(ReportData, ParetoFrontIsTheRowsNothingBeatsInErrorAndTime) {
  // (error, ms): a (0.1, 9) and c (0.3, 1) and b (0.2, 3) are each best
  // somewhere; d (0.25, 5) is beaten by b in both; e equals b and is kept.
  std::vector<ReportRow> rows = {row("virtual", 10, 0.1, 9), row("virtual", 20, 0.2, 3),
                                 row("voxel", 10, 0.3, 1), row("voxel", 20, 0.25, 5),
                                 row("voxel", 30, 0.2, 3)};
  mark_pareto(rows);
  EXPECT_TRUE(rows[0].pareto);
  EXPECT_TRUE(rows[1].pareto);
  EXPECT_TRUE(rows[2].pareto);
  EXPECT_FALSE(rows[3].pareto);
  EXPECT_TRUE(rows[4].pareto);  // ties beat nobody
}

TEST(ReportData, PatchModesArePairedAtTheSameTargetDenseAndAuto) {
  ReportData d;
  d.rows = {row("virtual", 150, 0.12, 1),
            row("virtual", 150, 0.5, 1, "1"),
            row("virtual", 150, 0.2, 1, "auto", "paper"),
            row("voxel", 150, 0.16, 1),
            row("virtual", 300, 0.1, 1),
            row("voxel", 300, 0.25, 1),
            row("virtual", 600, 0.1, 1)};
  d.rows[0].layout_indirect_error = 0.11;
  d.rows[3].layout_indirect_error = 0.13;
  const std::vector<PatchModeComparison> pairs = compare_patch_modes(d);
  ASSERT_EQ(pairs.size(), 2u);  // 600 has no voxel row
  EXPECT_EQ(pairs[0].patches_target, 150);
  EXPECT_EQ(pairs[0].virtual_layout_error, 0.11);
  EXPECT_EQ(pairs[0].voxel_layout_error, 0.13);
  EXPECT_DOUBLE_EQ(pairs[0].ratio(), 0.12 / 0.16);
  EXPECT_EQ(pairs[1].patches_target, 300);
  EXPECT_DOUBLE_EQ(pairs[1].ratio(), 0.1 / 0.25);
  // The paper's measure: the ratio of MSE, 0.63 on its Cornell box = 0.80 in RMSE.
  EXPECT_DOUBLE_EQ(pairs[1].mse_ratio(), (0.1 / 0.25) * (0.1 / 0.25));
  EXPECT_EQ(compare_patch_modes(d, "1").size(), 0u);
}

TEST(ReportData, RowSettingsRebuildTheRowsBake) {
  ReportRow r = row("voxel", 300, 0.1, 1, "inf", "ours");
  r.kept_fraction = 0.02;
  r.seed = 7;
  const BakeSettings s = report_row_settings(r);
  EXPECT_EQ(s.patches_total, 300);
  EXPECT_EQ(s.patch_mode, PatchMode::Voxel);
  EXPECT_EQ(s.transport.bounces, TransportSettings::kInfiniteBounces);
  EXPECT_EQ(s.codec, CodecChoice::LightWeighted);
  EXPECT_EQ(s.kept_fraction, 0.02);
  EXPECT_EQ(s.seed, 7u);
  EXPECT_EQ(report_row_settings(row("virtual", 60, 0.1, 1, "3")).transport.bounces, 3);
}

TEST(ReportData, JsonRoundTripAndErrorsNameTheFile) {
  ReportData d;
  d.scene_name = "box";
  d.reference.samples_per_pixel = 128;
  d.reference.noise_floor_indirect = 0.3;
  d.rows = {row("virtual", 60, 0.2, 1.5), row("voxel", 60, 0.3, 0.5, "2", "ours")};
  d.rows[1].kept_fraction = 0.08;
  d.rows[1].multiply_ms = 0.25;
  d.rows[1].matrix_bytes = 1234;
  d.rows[1].seed = 5;
  d.rows[1].layout_indirect_error = 0.125;
  d.rows[1].layout_vertex_error = 0.25;
  d.rows[1].compression_light_error = 0.0175;
  d.rows[1].probe_error = 0.0625;
  d.rows[1].probe_level = 0.96875;
  d.rows[1].probes = 138;
  d.reference.probe_points = 46;
  mark_pareto(d.rows);
  const ReportData back = report_from_json(report_to_json(d), "test");
  EXPECT_EQ(back.scene_name, "box");
  EXPECT_EQ(back.reference.samples_per_pixel, 128);
  EXPECT_DOUBLE_EQ(back.reference.noise_floor_indirect, 0.3);
  ASSERT_EQ(back.rows.size(), 2u);
  EXPECT_EQ(back.rows[1].mode, "voxel");
  EXPECT_EQ(back.rows[1].bounces, "2");
  EXPECT_EQ(back.rows[1].codec_name, "ours");
  EXPECT_EQ(back.rows[1].kept_fraction, 0.08);
  EXPECT_FALSE(back.rows[0].kept_fraction);
  EXPECT_DOUBLE_EQ(back.rows[1].update_ms(), 0.75);
  EXPECT_EQ(back.rows[1].matrix_bytes, 1234u);
  EXPECT_EQ(back.rows[1].seed, 5u);
  EXPECT_EQ(back.rows[0].seed, 1u);
  EXPECT_EQ(back.rows[1].layout_indirect_error, 0.125);
  EXPECT_EQ(back.rows[1].layout_vertex_error, 0.25);
  EXPECT_EQ(back.rows[1].compression_light_error, 0.0175);
  EXPECT_EQ(back.rows[0].compression_light_error, 0.0);
  EXPECT_EQ(back.rows[0].layout_indirect_error, 0.0);
  EXPECT_EQ(back.rows[0].pareto, d.rows[0].pareto);
  EXPECT_EQ(back.rows[1].probe_error, 0.0625);
  EXPECT_EQ(back.rows[1].probe_level, 0.96875);
  EXPECT_EQ(back.rows[1].probes, 138u);
  EXPECT_EQ(back.rows[0].probes, 0u);
  EXPECT_EQ(back.reference.probe_points, 46u);

  const test::ScratchDir dir("bounce-report-data");
  const auto bad = dir / "report.json";
  {
    std::ofstream out(bad);
    out << R"({"scene": {"name": "x"}, "reference": {}, "rows": [{"mode": "virtual"}]})";
  }
  try {
    read_report(bad);
    FAIL() << "a row without fields was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_report(dir / "missing.json"), Error);
}

}  // namespace
}  // namespace bounce
