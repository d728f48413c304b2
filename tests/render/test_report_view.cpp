// The report's pictures: `bounce report` writes its three PNG plots under an
// X server (and, without one, the table and one line saying why there are no
// plots); the studio's report view draws each row's point where the chart's
// axes say, a click on a point selects that row, and `bounce-studio --view
// report --report FILE` renders it.
#include <QMouseEvent>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "render_support.h"
#include "report/report_data.h"
#include "report_charts.h"
#include "report_view.h"

namespace bounce::render_test {

namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::array<int, 3> rgb(const std::array<unsigned char, 3>& c) { return {c[0], c[1], c[2]}; }

std::size_t count_lines_with(const std::string& text, const std::string& needle) {
  std::size_t n = 0, at = 0;
  while ((at = text.find(needle, at)) != std::string::npos) {
    ++n;
    at += needle.size();
  }
  return n;
}

// A report with rows whose values are chosen here, so where each point must
// appear is known without the code under test: errors 0.1 .. 0.4, update
// times 1 .. 8 ms, one virtual and one voxel series.
ReportData known_report() {
  ReportData d;
  d.scene_name = "known";
  const struct {
    const char* mode;
    double error, ms;
    const char* bounces;
    const char* codec;
  } rows[] = {{"virtual", 0.10, 8.0, "auto", "dense"},
              {"virtual", 0.20, 2.0, "2", "dense"},
              {"virtual", 0.30, 4.0, "auto", "paper"},
              {"voxel", 0.40, 1.0, "1", "dense"},
              {"voxel", 0.25, 6.0, "inf", "dense"}};
  int target = 100;
  for (const auto& s : rows) {
    ReportRow r;
    r.mode = s.mode;
    r.patches_target = target;
    r.patches = static_cast<std::size_t>(target + 3);
    target += 50;
    r.bounces = s.bounces;
    r.codec_name = s.codec;
    r.codec = s.codec;
    r.direct_ms = s.ms;
    r.indirect_error = s.error;
    r.matrix_bytes = 4096;
    d.rows.push_back(r);
  }
  mark_pareto(d.rows);
  return d;
}

}  // namespace

class ReportView : public RenderTest {};

TEST_F(ReportView, PointsAreDrawnWhereTheAxesPutThemAndAClickSelectsTheRow) {
  views::ReportView view;
  view.resize(800, 600);
  view.show();
  const auto report = std::make_shared<const ReportData>(known_report());
  view.set_report(report);
  settle();
  const QImage image = view.chart_widget()->grab().toImage();
  ASSERT_EQ(image.size(), view.chart_widget()->size());
  image.save(QString::fromStdString((work_dir("report-view") / "chart.png").string()));
  for (std::size_t i = 0; i < report->rows.size(); ++i) {
    const ReportRow& row = report->rows[i];
    const std::optional<QPoint> p = view.point_position(i);
    ASSERT_TRUE(p) << "row " << i;
    ASSERT_TRUE(image.rect().contains(*p)) << "row " << i;
    // The marker is centred there: its middle has the series colour.
    const QColor c = image.pixelColor(*p);
    const auto want = row.mode == "voxel" ? views::kVoxelSeriesColour : views::kVirtualSeriesColour;
    EXPECT_NEAR(c.red(), want[0], 12) << "row " << i << " at " << p->x() << "," << p->y();
    EXPECT_NEAR(c.green(), want[1], 12) << "row " << i;
    EXPECT_NEAR(c.blue(), want[2], 12) << "row " << i;
  }
  // More error is higher up, more time further right (Qt's y grows downwards).
  EXPECT_LT(view.point_position(3)->y(), view.point_position(0)->y());  // 0.40 above 0.10
  EXPECT_GT(view.point_position(0)->x(), view.point_position(1)->x());  // 8 ms right of 2 ms

  // A click (press and release) on row 2's point selects row 2.
  std::vector<int> clicked;
  QObject::connect(&view, &views::ReportView::row_clicked,
                   [&clicked](int row) { clicked.push_back(row); });
  const QPoint at = *view.point_position(2);
  QMouseEvent press(QEvent::MouseButtonPress, at, Qt::LeftButton, Qt::LeftButton, Qt::NoModifier);
  QMouseEvent release(QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton, Qt::NoModifier);
  QApplication::sendEvent(view.chart_widget(), &press);
  QApplication::sendEvent(view.chart_widget(), &release);
  settle();
  ASSERT_EQ(clicked.size(), 1u);
  EXPECT_EQ(clicked.front(), 2);
  // Far from every point: nothing.
  EXPECT_FALSE(view.row_at(QPoint(2, 2)));

  // The clicked row's bake settings: what the panel receives.
  const BakeSettings s = report_row_settings(report->rows[2]);
  EXPECT_EQ(s.patches_total, report->rows[2].patches_target);
  EXPECT_EQ(s.patch_mode, PatchMode::Virtual);
  EXPECT_EQ(s.codec, CodecChoice::LargestEntries);
  EXPECT_EQ(s.transport.bounces, TransportSettings::kAutoBounces);
  EXPECT_EQ(report_row_settings(report->rows[3]).patch_mode, PatchMode::Voxel);
  EXPECT_EQ(report_row_settings(report->rows[3]).transport.bounces, 1);
}

// `bounce report` at small settings (dense, auto bounces): the table, three non-blank plots with
// both series' points in them, errors positive and finite, and virtual
// patches beating the voxel baseline at the larger matched patch count; then
// the studio shows the same report.json; then, without a display, the table
// comes with one line saying why there are no plots.
TEST_F(ReportView, CliReportWritesPlotsAndTheStudioShowsIt) {
  const fs::path dir = work_dir("report");
  const std::string common = " report " + std::string(BOUNCE_RESOURCE_DIR) +
                             "/scenes/cornell-box --quick --bounces auto -q --cache " +
                             (fs::path(BOUNCE_RENDER_WORK) / "reference-cache").string();
  const CommandRun r = run_command(std::string(BOUNCE_CLI) + common + " --codecs dense --out " +
                                   (dir / "r").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const ReportData report = read_report(dir / "r" / "report.json");
  ASSERT_EQ(report.rows.size(), 2u * 2u);  // modes x patch counts
  for (const ReportRow& row : report.rows) {
    EXPECT_TRUE(std::isfinite(row.indirect_error) && row.indirect_error > 0.0) << row.codec;
    EXPECT_TRUE(std::isfinite(row.vertex_error) && row.vertex_error > 0.0) << row.codec;
    EXPECT_GT(row.update_ms(), 0.0);
  }
  const std::vector<PatchModeComparison> pairs = compare_patch_modes(report);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_LT(pairs.back().virtual_error, pairs.back().voxel_error)
      << "virtual patches should beat the voxel baseline at target " << pairs.back().patches_target;

  const std::string md = read_text(dir / "r" / "report.md");
  for (const char* name : {"error_vs_runtime.png", "error_vs_memory.png", "virtual_vs_voxel.png"}) {
    EXPECT_NE(md.find(std::string("](") + name + ")"), std::string::npos) << name;
    const QImage png(QString::fromStdString((dir / "r" / name).string()));
    ASSERT_FALSE(png.isNull()) << name;
    EXPECT_EQ(png.size(), QSize(800, 600)) << name;
    EXPECT_GT(non_uniform_share(png), 0.02) << name << " looks blank";
    // Each series' markers (10 px across) show in its colour.
    EXPECT_GT(count_colour(png, rgb(views::kVirtualSeriesColour), 8), 20u) << name;
    EXPECT_GT(count_colour(png, rgb(views::kVoxelSeriesColour), 8), 20u) << name;
  }

  // The studio's report view of that file.
  const fs::path shot = dir / "studio.png";
  const CommandRun s =
      run_command(std::string(BOUNCE_STUDIO) + " " + BOUNCE_RESOURCE_DIR +
                  "/scenes/cornell-box --screenshot " + shot.string() +
                  " --view report --size 640x480 --report " + (dir / "r" / "report.json").string());
  ASSERT_EQ(s.code, 0) << s.output;
  const QImage studio(QString::fromStdString(shot.string()));
  ASSERT_EQ(studio.size(), QSize(640, 480));
  EXPECT_GT(count_colour(studio, rgb(views::kVirtualSeriesColour), 8), 20u);
  EXPECT_GT(count_colour(studio, rgb(views::kVoxelSeriesColour), 8), 20u);

  // No display: the numbers, no plots, and the reason said once.
  const CommandRun n =
      run_command("env -u DISPLAY " + std::string(BOUNCE_CLI) + common +
                  " --patches 60 --modes virtual --codecs dense --out " + (dir / "n").string());
  ASSERT_EQ(n.code, 0) << n.output;
  EXPECT_EQ(count_lines_with(n.output, "no plots"), 1u) << n.output;
  EXPECT_TRUE(fs::exists(dir / "n" / "report.md"));
  EXPECT_FALSE(fs::exists(dir / "n" / "error_vs_runtime.png"));
  EXPECT_NE(read_text(dir / "n" / "report.md").find("No plots: "), std::string::npos);
}

}  // namespace bounce::render_test
