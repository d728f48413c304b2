#pragma once
// The plots of `bounce report` as VTK charts, drawn from the
// core's report rows (report/report_data.h): error against run time with the
// Pareto front, error against memory, and virtual patches against the voxel
// baseline by patch count (the paper's Table 3 comparison). The same chart
// objects are drawn offscreen into PNGs for report.md and shown in the
// studio's report view.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <vtkSmartPointer.h>

#include "bounce/report.h"

class vtkChartXY;

namespace bounce::views {

// Series colours, 8-bit RGB: tests look for them in the pictures.
inline constexpr std::array<unsigned char, 3> kVirtualSeriesColour{31, 119, 180};  // blue
inline constexpr std::array<unsigned char, 3> kVoxelSeriesColour{214, 39, 40};     // red
inline constexpr std::array<unsigned char, 3> kParetoSeriesColour{0, 0, 0};        // black

// Which plot of the row list each chart point is: the chart's series are
// "virtual" and "voxel" points; row_of_point maps (series, index) to the row.
struct ReportChartPoints {
  std::vector<std::size_t> virtual_rows, voxel_rows;
};

// Noise-corrected indirect error against update time, one point per row, a
// point series per patch mode, and the Pareto front as a line.
vtkSmartPointer<vtkChartXY> make_error_runtime_chart(const ReportData& report,
                                                     ReportChartPoints* points = nullptr);
// The same error against the stored matrix's size (KiB, log axis).
vtkSmartPointer<vtkChartXY> make_error_memory_chart(const ReportData& report);
// Error against actual patch count for the dense, auto-bounce rows: virtual
// and voxel as lines (compare_patch_modes: matched target counts).
vtkSmartPointer<vtkChartXY> make_patch_mode_chart(const ReportData& report);

// Draws a chart offscreen (needs an X display on Debian's VTK) and returns
// the PNG bytes. Throws bounce::Error when VTK reports an error.
std::vector<unsigned char> render_chart_png(vtkChartXY& chart, int width, int height);

// Writes error_vs_runtime.png, error_vs_memory.png and virtual_vs_voxel.png
// (atomically) into `folder`; returns their paths.
std::vector<std::filesystem::path> write_report_charts(const ReportData& report,
                                                       const std::filesystem::path& folder,
                                                       int width = 800, int height = 600);

}  // namespace bounce::views
