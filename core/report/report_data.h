#pragma once
// What `bounce report` measures, as data: one row per setting (patch mode,
// patch count, bounces, codec) with its bake time, update time, matrix size
// and errors against the path-traced reference. Written to and read from
// report.json here, so the CLI's table, the plots (views/report_charts.h)
// and the studio's report view all work from the same rows.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "metrics/image_metrics.h"
#include "metrics/vertex_metrics.h"
#include "settings/bake_settings.h"

namespace bounce {

struct ReportRow {
  std::string mode;                     // virtual, voxel
  int patches_target = 0;               // --patches-total of the row
  std::size_t patches = 0;              // patches the bake made
  std::string bounces;                  // 1, 2, 3, auto, inf
  std::string codec_name;               // dense, paper, ours
  std::optional<double> kept_fraction;  // set when the sweep fixed it
  std::uint64_t seed = 1;               // sampling seed of the row's bake
  std::string codec;                    // label: "dense", "ours (budget)", "ours 2%"
  double bake_seconds = 0.0;
  double direct_ms = 0.0, multiply_ms = 0.0;
  std::size_t matrix_bytes = 0;
  // The compressed matrix's relative RMS error of the indirect light on the
  // worst evaluation light, against the exact matrix (what the error budget
  // bounds); 0 for dense and in reports from before.
  double compression_light_error = 0.0;
  double indirect_power = 0.0;  // area-weighted, R+G+B, of T b
  ImageErrors full, indirect;
  VertexErrors vertex;
  // Relative RMSE with the reference's own noise taken out (metrics): what
  // the table shows, the plots draw and the Pareto front uses.
  double indirect_error = 0.0, vertex_error = 0.0;
  // The same two errors with exact patch values (report/exact_patch_light.h):
  // the patch layout's share, which no transport accuracy goes below; the
  // rest of the row's error is the transport's. 0 in reports from before.
  double layout_indirect_error = 0.0, layout_vertex_error = 0.0;
  // How patch light reached pixels and vertices: "final gather"
  // (runtime/final_gather.h) or "nearest patches" (runtime/patch_gather.h).
  std::string transfer = "nearest patches";
  // Mean indirect light against the reference's mean (1 = the right level):
  // over the picture's covered pixels (R+G+B) and over the vertices.
  double indirect_level = 0.0, vertex_level = 0.0;
  double layout_indirect_level = 0.0, layout_vertex_level = 0.0;  // with exact patch values
  // The light probes' SH blended at the report's probe points against the
  // reference there (report/report_probes.h): relative RMSE with the
  // reference's noise taken out, and the mean level. 0: not measured.
  double probe_error = 0.0, probe_level = 0.0;
  std::size_t probes = 0;  // the row's light probes
  bool pareto = false;
  double update_ms() const { return direct_ms + multiply_ms; }
};

// The reference a report measured against (docs/reference.md).
struct ReportReference {
  int samples_per_pixel = 0, samples_per_vertex = 0;
  int width = 0, height = 0;
  std::size_t vertices = 0;
  std::size_t probe_points = 0;  // points of the probe column, 0 without it
  bool images_from_cache = false, vertices_from_cache = false;
  std::string cache;
  double seconds = 0.0;
  double noise_floor_full = 0.0, noise_floor_indirect = 0.0;
};

struct ReportData {
  std::string scene_name, scene_path;
  std::size_t triangles = 0;
  ReportReference reference;
  std::vector<ReportRow> rows;
  double seconds = 0.0;  // the whole sweep
};

// Marks the rows no other row beats on both indirect error and update time.
void mark_pareto(std::vector<ReportRow>& rows);

// The settings a standalone `bounce bake` of the row uses (what the studio
// loads into its panel when a point of the chart is clicked).
BakeSettings report_row_settings(const ReportRow& row);

// Virtual patches against the voxel baseline at the same patch count (the
// paper's Table 3): for every virtual row at dense storage and `bounces`
// (auto by default), the voxel row of the same target count and bounces.
struct PatchModeComparison {
  int patches_target = 0;
  std::size_t virtual_patches = 0, voxel_patches = 0;
  double virtual_error = 0.0, voxel_error = 0.0;  // noise-corrected indirect rel. RMSE
  // The same with exact patch values (ReportRow::layout_indirect_error).
  double virtual_layout_error = 0.0, voxel_layout_error = 0.0;
  double ratio() const { return voxel_error > 0.0 ? virtual_error / voxel_error : 0.0; }
  // The ratio of mean squared errors (ratio()^2), the measure of the paper's
  // Table 3 (MSE 4.90 against 7.73 on its Cornell box: 0.63, 0.80 in RMSE).
  double mse_ratio() const { return ratio() * ratio(); }
};
std::vector<PatchModeComparison> compare_patch_modes(const ReportData& report,
                                                     const std::string& bounces = "auto");

nlohmann::ordered_json report_to_json(const ReportData& report);
// Throws bounce::Error naming `where` and the missing or mistyped field.
ReportData report_from_json(const nlohmann::json& json, const std::string& where);
// Reads report.json; throws bounce::Error naming the file.
ReportData read_report(const std::filesystem::path& file);

}  // namespace bounce
