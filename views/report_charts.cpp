#include "report_charts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include "bounce/error.h"
#include "bounce/export.h"
#include "vtk_error_capture.h"

namespace bounce::views {

namespace {

namespace fs = std::filesystem;

struct Series {
  std::string name;
  std::vector<double> x, y;
};

vtkSmartPointer<vtkTable> table_of(const Series& s, const std::string& x_name,
                                   const std::string& y_name) {
  auto table = vtkSmartPointer<vtkTable>::New();
  vtkNew<vtkFloatArray> x, y;
  x->SetName(x_name.c_str());
  y->SetName((y_name + " " + s.name).c_str());
  table->AddColumn(x);
  table->AddColumn(y);
  table->SetNumberOfRows(static_cast<vtkIdType>(s.x.size()));
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    table->SetValue(static_cast<vtkIdType>(i), 0, s.x[i]);
    table->SetValue(static_cast<vtkIdType>(i), 1, s.y[i]);
  }
  return table;
}

// A plot keeps its table alive (it holds a reference to its input).
void add_series(vtkChartXY& chart, const Series& s, int type,
                const std::array<unsigned char, 3>& colour, const std::string& x_name,
                const std::string& y_name, float width, int marker) {
  if (s.x.empty()) return;  // an empty table makes VTK complain about its bounds
  // VTK refuses to draw a line through one point: draw it as a point.
  if (type == vtkChart::LINE && s.x.size() < 2) {
    type = vtkChart::POINTS;
    if (marker == vtkPlotPoints::NONE) marker = vtkPlotPoints::PLUS;
  }
  vtkPlot* plot = chart.AddPlot(type);
  plot->SetInputData(table_of(s, x_name, y_name), 0, 1);
  plot->SetColor(colour[0], colour[1], colour[2], 255);
  plot->SetWidth(width);
  plot->SetLabel(s.name);
  if (auto* points = vtkPlotPoints::SafeDownCast(plot)) {
    points->SetMarkerStyle(marker);
    if (marker != vtkPlotPoints::NONE) points->SetMarkerSize(10.0f);
  }
}

vtkSmartPointer<vtkChartXY> new_chart(const std::string& title, const std::string& x_title,
                                      const std::string& y_title) {
  auto chart = vtkSmartPointer<vtkChartXY>::New();
  chart->SetTitle(title);
  chart->GetTitleProperties()->SetFontSize(16);
  chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(x_title);
  chart->GetAxis(vtkAxis::LEFT)->SetTitle(y_title);
  chart->SetShowLegend(true);
  chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  return chart;
}

// Errors start at zero: the eye compares heights from there.
void error_axis_from_zero(vtkChartXY& chart, const ReportData& report) {
  double top = 0.0;
  for (const ReportRow& r : report.rows)
    if (std::isfinite(r.indirect_error)) top = std::max(top, r.indirect_error);
  vtkAxis* y = chart.GetAxis(vtkAxis::LEFT);
  y->SetBehavior(vtkAxis::FIXED);
  y->SetRange(0.0, top > 0.0 ? 1.1 * top : 1.0);
}

// A fixed range with room around the data, so the markers of the extreme
// points are drawn whole (the plot area clips them).
void pad_axis(vtkChartXY& chart, int axis, const std::vector<double>& values, bool from_zero,
              bool log) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : values)
    if (std::isfinite(v) && (!log || v > 0.0)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  if (!(lo <= hi)) return;
  vtkAxis* a = chart.GetAxis(axis);
  a->SetBehavior(vtkAxis::FIXED);
  if (log) {
    a->SetUnscaledRange(lo / 1.4, hi * 1.4);
    return;
  }
  const double span = hi > lo ? hi - lo : std::max(std::abs(hi), 1.0);
  a->SetRange(from_zero ? 0.0 : lo - 0.05 * span, hi + 0.05 * span);
}

constexpr const char* kErrorTitle = "indirect light error (relative RMSE, noise removed)";

}  // namespace

vtkSmartPointer<vtkChartXY> make_error_runtime_chart(const ReportData& report,
                                                     ReportChartPoints* points) {
  auto chart = new_chart("Error against run time: " + report.scene_name,
                         "one light update (ms: direct light + T b)", kErrorTitle);
  Series virt{"virtual patches", {}, {}}, voxel{"voxel patches", {}, {}},
      pareto{"Pareto front", {}, {}};
  ReportChartPoints map;
  std::vector<const ReportRow*> front;
  for (std::size_t i = 0; i < report.rows.size(); ++i) {
    const ReportRow& r = report.rows[i];
    if (!std::isfinite(r.indirect_error)) continue;
    Series& s = r.mode == "voxel" ? voxel : virt;
    s.x.push_back(r.update_ms());
    s.y.push_back(r.indirect_error);
    (r.mode == "voxel" ? map.voxel_rows : map.virtual_rows).push_back(i);
    if (r.pareto) front.push_back(&r);
  }
  std::sort(front.begin(), front.end(),
            [](const ReportRow* a, const ReportRow* b) { return a->update_ms() < b->update_ms(); });
  for (const ReportRow* r : front) {
    pareto.x.push_back(r->update_ms());
    pareto.y.push_back(r->indirect_error);
  }
  // The front first, so the points are drawn over it.
  add_series(*chart, pareto, vtkChart::LINE, kParetoSeriesColour, "ms", "error", 2.0f,
             vtkPlotPoints::NONE);
  add_series(*chart, virt, vtkChart::POINTS, kVirtualSeriesColour, "ms", "error", 1.0f,
             vtkPlotPoints::CIRCLE);
  add_series(*chart, voxel, vtkChart::POINTS, kVoxelSeriesColour, "ms", "error", 1.0f,
             vtkPlotPoints::SQUARE);
  error_axis_from_zero(*chart, report);
  std::vector<double> ms = virt.x;
  ms.insert(ms.end(), voxel.x.begin(), voxel.x.end());
  pad_axis(*chart, vtkAxis::BOTTOM, ms, /*from_zero=*/true, /*log=*/false);
  if (points) *points = std::move(map);
  return chart;
}

vtkSmartPointer<vtkChartXY> make_error_memory_chart(const ReportData& report) {
  auto chart = new_chart("Error against memory: " + report.scene_name,
                         "stored transport matrix (KiB, log scale)", kErrorTitle);
  Series virt{"virtual patches", {}, {}}, voxel{"voxel patches", {}, {}};
  for (const ReportRow& r : report.rows) {
    if (!std::isfinite(r.indirect_error) || r.matrix_bytes == 0) continue;
    Series& s = r.mode == "voxel" ? voxel : virt;
    s.x.push_back(static_cast<double>(r.matrix_bytes) / 1024.0);
    s.y.push_back(r.indirect_error);
  }
  add_series(*chart, virt, vtkChart::POINTS, kVirtualSeriesColour, "KiB", "error", 1.0f,
             vtkPlotPoints::CIRCLE);
  add_series(*chart, voxel, vtkChart::POINTS, kVoxelSeriesColour, "KiB", "error", 1.0f,
             vtkPlotPoints::SQUARE);
  chart->GetAxis(vtkAxis::BOTTOM)->SetLogScale(true);
  std::vector<double> kib = virt.x;
  kib.insert(kib.end(), voxel.x.begin(), voxel.x.end());
  pad_axis(*chart, vtkAxis::BOTTOM, kib, /*from_zero=*/false, /*log=*/true);
  error_axis_from_zero(*chart, report);
  return chart;
}

vtkSmartPointer<vtkChartXY> make_patch_mode_chart(const ReportData& report) {
  auto chart = new_chart("Virtual patches against the voxel baseline: " + report.scene_name,
                         "patches", kErrorTitle + std::string(", dense, auto bounces"));
  Series virt{"virtual patches", {}, {}}, voxel{"voxel patches", {}, {}};
  for (const PatchModeComparison& c : compare_patch_modes(report)) {
    virt.x.push_back(static_cast<double>(c.virtual_patches));
    virt.y.push_back(c.virtual_error);
    voxel.x.push_back(static_cast<double>(c.voxel_patches));
    voxel.y.push_back(c.voxel_error);
  }
  // Lines over patch count need increasing x.
  for (Series* s : {&virt, &voxel}) {
    std::vector<std::size_t> order(s->x.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return s->x[a] < s->x[b]; });
    Series sorted{s->name, {}, {}};
    for (std::size_t i : order) {
      sorted.x.push_back(s->x[i]);
      sorted.y.push_back(s->y[i]);
    }
    *s = sorted;
  }
  add_series(*chart, virt, vtkChart::LINE, kVirtualSeriesColour, "patches", "error", 2.0f,
             vtkPlotPoints::CIRCLE);
  add_series(*chart, voxel, vtkChart::LINE, kVoxelSeriesColour, "patches", "error", 2.0f,
             vtkPlotPoints::SQUARE);
  std::vector<double> counts = virt.x;
  counts.insert(counts.end(), voxel.x.begin(), voxel.x.end());
  pad_axis(*chart, vtkAxis::BOTTOM, counts, /*from_zero=*/false, /*log=*/false);
  error_axis_from_zero(*chart, report);
  return chart;
}

std::vector<unsigned char> render_chart_png(vtkChartXY& chart, int width, int height) {
  VtkErrorCapture::install();
  VtkErrorCapture::clear();
  vtkNew<vtkContextView> view;
  view->GetRenderWindow()->SetOffScreenRendering(1);
  view->GetRenderWindow()->SetSize(width, height);
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  view->GetScene()->AddItem(&chart);
  view->GetRenderWindow()->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(view->GetRenderWindow());
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkNew<vtkPNGWriter> png;
  png->WriteToMemoryOn();
  png->SetInputConnection(grab->GetOutputPort());
  png->Write();
  view->GetScene()->RemoveItem(&chart);
  const std::vector<std::string> vtk = VtkErrorCapture::messages();
  if (!vtk.empty()) throw Error("plot", "VTK reported: " + vtk.front());
  vtkUnsignedCharArray* bytes = png->GetResult();
  if (!bytes || bytes->GetNumberOfValues() == 0) throw Error("plot", "VTK wrote no PNG");
  const unsigned char* p = bytes->GetPointer(0);
  return std::vector<unsigned char>(p, p + bytes->GetNumberOfValues());
}

std::vector<fs::path> write_report_charts(const ReportData& report, const fs::path& folder,
                                          int width, int height) {
  const std::vector<std::pair<std::string, vtkSmartPointer<vtkChartXY>>> charts = {
      {"error_vs_runtime.png", make_error_runtime_chart(report)},
      {"error_vs_memory.png", make_error_memory_chart(report)},
      {"virtual_vs_voxel.png", make_patch_mode_chart(report)}};
  std::vector<fs::path> written;
  for (const auto& [name, chart] : charts) {
    const std::vector<unsigned char> png = render_chart_png(*chart, width, height);
    AtomicFile file(folder / name);
    file.stream().write(reinterpret_cast<const char*>(png.data()),
                        static_cast<std::streamsize>(png.size()));
    file.commit();
    written.push_back(folder / name);
  }
  return written;
}

}  // namespace bounce::views
