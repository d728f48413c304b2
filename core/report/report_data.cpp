#include "report/report_data.h"

#include <cmath>
#include <fstream>

#include "base/error.h"
#include "transport/transport_settings.h"

namespace bounce {

using nlohmann::json;
using nlohmann::ordered_json;

void mark_pareto(std::vector<ReportRow>& rows) {
  for (ReportRow& r : rows) {
    r.pareto = std::isfinite(r.indirect_error);
    for (const ReportRow& o : rows) {
      if (&o == &r) continue;
      const bool no_worse = o.indirect_error <= r.indirect_error && o.update_ms() <= r.update_ms();
      const bool better = o.indirect_error < r.indirect_error || o.update_ms() < r.update_ms();
      if (no_worse && better) {
        r.pareto = false;
        break;
      }
    }
  }
}

BakeSettings report_row_settings(const ReportRow& row) {
  BakeSettings s;
  s.patches_total = row.patches_target;
  s.patch_mode = row.mode == "voxel" ? PatchMode::Voxel : PatchMode::Virtual;
  if (row.bounces == "auto")
    s.transport.bounces = TransportSettings::kAutoBounces;
  else if (row.bounces == "inf")
    s.transport.bounces = TransportSettings::kInfiniteBounces;
  else
    s.transport.bounces = std::stoi(row.bounces);
  s.codec = row.codec_name == "paper"   ? CodecChoice::LargestEntries
            : row.codec_name == "ours"  ? CodecChoice::LightWeighted
            : row.codec_name == "dense" ? CodecChoice::Dense
                                        : CodecChoice::Auto;
  s.kept_fraction = row.kept_fraction;
  s.seed = row.seed;
  return s;
}

std::vector<PatchModeComparison> compare_patch_modes(const ReportData& report,
                                                     const std::string& bounces) {
  std::vector<PatchModeComparison> out;
  for (const ReportRow& v : report.rows) {
    if (v.mode != "virtual" || v.codec_name != "dense" || v.bounces != bounces) continue;
    for (const ReportRow& x : report.rows)
      if (x.mode == "voxel" && x.codec_name == "dense" && x.bounces == bounces &&
          x.patches_target == v.patches_target) {
        out.push_back({v.patches_target, v.patches, x.patches, v.indirect_error, x.indirect_error,
                       v.layout_indirect_error, x.layout_indirect_error});
        break;
      }
  }
  return out;
}

namespace {

ordered_json errors_json(const ImageErrors& e) {
  return {{"mse", e.mse},   {"rmse", e.rmse}, {"relative_rmse", e.relative_rmse},
          {"psnr", e.psnr}, {"ssim", e.ssim}, {"pixels", e.pixels}};
}

ImageErrors errors_from(const json& j) {
  ImageErrors e;
  e.mse = j.at("mse").get<double>();
  e.rmse = j.at("rmse").get<double>();
  e.relative_rmse = j.at("relative_rmse").get<double>();
  e.psnr = j.at("psnr").get<double>();
  e.ssim = j.at("ssim").get<double>();
  e.pixels = j.at("pixels").get<std::size_t>();
  return e;
}

// Labels of rows written before codec_name existed: "ours (budget)", "ours 2%".
std::string codec_name_of(const std::string& label) { return label.substr(0, label.find(' ')); }

}  // namespace

ordered_json report_to_json(const ReportData& report) {
  ordered_json j;
  j["scene"] = {
      {"name", report.scene_name}, {"path", report.scene_path}, {"triangles", report.triangles}};
  const ReportReference& r = report.reference;
  j["reference"] = {{"samples_per_pixel", r.samples_per_pixel},
                    {"samples_per_vertex", r.samples_per_vertex},
                    {"width", r.width},
                    {"height", r.height},
                    {"vertices", r.vertices},
                    {"probe_points", r.probe_points},
                    {"images_from_cache", r.images_from_cache},
                    {"vertices_from_cache", r.vertices_from_cache},
                    {"cache", r.cache},
                    {"seconds", r.seconds},
                    {"noise_floor_full_relative_rmse", r.noise_floor_full},
                    {"noise_floor_indirect_relative_rmse", r.noise_floor_indirect}};
  ordered_json rows = ordered_json::array();
  for (const ReportRow& row : report.rows)
    rows.push_back(
        {{"mode", row.mode},
         {"patches_target", row.patches_target},
         {"patches", row.patches},
         {"bounces", row.bounces},
         {"codec", row.codec},
         {"codec_name", row.codec_name},
         {"kept_fraction", row.kept_fraction ? ordered_json(*row.kept_fraction) : ordered_json()},
         {"seed", row.seed},
         {"bake_seconds", row.bake_seconds},
         {"update_ms", row.update_ms()},
         {"direct_ms", row.direct_ms},
         {"multiply_ms", row.multiply_ms},
         {"matrix_bytes", row.matrix_bytes},
         {"compression_light_rel_rms_max", row.compression_light_error},
         {"indirect_power", row.indirect_power},
         {"image_full", errors_json(row.full)},
         {"image_indirect", errors_json(row.indirect)},
         {"image_indirect_noise_corrected_relative_rmse", row.indirect_error},
         {"vertex_indirect_noise_corrected_relative_rmse", row.vertex_error},
         {"layout_image_indirect_noise_corrected_relative_rmse", row.layout_indirect_error},
         {"layout_vertex_indirect_noise_corrected_relative_rmse", row.layout_vertex_error},
         {"transfer", row.transfer},
         {"image_indirect_level", row.indirect_level},
         {"vertex_indirect_level", row.vertex_level},
         {"layout_image_indirect_level", row.layout_indirect_level},
         {"layout_vertex_indirect_level", row.layout_vertex_level},
         {"probe_noise_corrected_relative_rmse", row.probe_error},
         {"probe_level", row.probe_level},
         {"probes", row.probes},
         {"vertex_indirect",
          {{"relative_rmse", row.vertex.relative_rmse},
           {"mean_relative", row.vertex.mean_relative},
           {"max_relative", row.vertex.max_relative},
           {"vertices", row.vertex.vertices}}},
         {"pareto", row.pareto}});
  j["rows"] = rows;
  j["seconds"] = report.seconds;
  return j;
}

ReportData report_from_json(const json& j, const std::string& where) {
  ReportData d;
  std::size_t index = 0;
  try {
    d.scene_name = j.at("scene").at("name").get<std::string>();
    d.scene_path = j.at("scene").value("path", std::string());
    d.triangles = j.at("scene").value("triangles", std::size_t{0});
    const json& r = j.at("reference");
    d.reference.samples_per_pixel = r.value("samples_per_pixel", 0);
    d.reference.samples_per_vertex = r.value("samples_per_vertex", 0);
    d.reference.width = r.value("width", 0);
    d.reference.height = r.value("height", 0);
    d.reference.vertices = r.value("vertices", std::size_t{0});
    d.reference.probe_points = r.value("probe_points", std::size_t{0});
    d.reference.images_from_cache = r.value("images_from_cache", false);
    d.reference.vertices_from_cache = r.value("vertices_from_cache", false);
    d.reference.cache = r.value("cache", std::string());
    d.reference.seconds = r.value("seconds", 0.0);
    d.reference.noise_floor_full = r.value("noise_floor_full_relative_rmse", 0.0);
    d.reference.noise_floor_indirect = r.value("noise_floor_indirect_relative_rmse", 0.0);
    for (const json& jr : j.at("rows")) {
      ReportRow row;
      row.mode = jr.at("mode").get<std::string>();
      if (row.mode != "virtual" && row.mode != "voxel")
        throw Error(where, "row " + std::to_string(index) + ": mode must be virtual or voxel");
      row.patches_target = jr.at("patches_target").get<int>();
      row.patches = jr.at("patches").get<std::size_t>();
      row.bounces = jr.at("bounces").get<std::string>();
      row.codec = jr.at("codec").get<std::string>();
      row.codec_name = jr.value("codec_name", codec_name_of(row.codec));
      if (jr.contains("kept_fraction") && !jr.at("kept_fraction").is_null())
        row.kept_fraction = jr.at("kept_fraction").get<double>();
      row.seed = jr.value("seed", std::uint64_t{1});  // reports before --seed used 1
      row.bake_seconds = jr.at("bake_seconds").get<double>();
      row.direct_ms = jr.at("direct_ms").get<double>();
      row.multiply_ms = jr.at("multiply_ms").get<double>();
      row.matrix_bytes = jr.at("matrix_bytes").get<std::size_t>();
      row.compression_light_error = jr.value("compression_light_rel_rms_max", 0.0);
      row.indirect_power = jr.value("indirect_power", 0.0);
      row.full = errors_from(jr.at("image_full"));
      row.indirect = errors_from(jr.at("image_indirect"));
      row.indirect_error = jr.at("image_indirect_noise_corrected_relative_rmse").get<double>();
      row.vertex_error = jr.at("vertex_indirect_noise_corrected_relative_rmse").get<double>();
      // Reports from before the layout errors have none (0).
      row.layout_indirect_error =
          jr.value("layout_image_indirect_noise_corrected_relative_rmse", 0.0);
      row.layout_vertex_error =
          jr.value("layout_vertex_indirect_noise_corrected_relative_rmse", 0.0);
      // Reports from before the final gather used the nearest patches.
      row.transfer = jr.value("transfer", std::string("nearest patches"));
      row.indirect_level = jr.value("image_indirect_level", 0.0);
      row.vertex_level = jr.value("vertex_indirect_level", 0.0);
      row.layout_indirect_level = jr.value("layout_image_indirect_level", 0.0);
      row.layout_vertex_level = jr.value("layout_vertex_indirect_level", 0.0);
      // Reports from before the probe column have none (0).
      row.probe_error = jr.value("probe_noise_corrected_relative_rmse", 0.0);
      row.probe_level = jr.value("probe_level", 0.0);
      row.probes = jr.value("probes", std::size_t{0});
      const json& v = jr.at("vertex_indirect");
      row.vertex.relative_rmse = v.at("relative_rmse").get<double>();
      row.vertex.mean_relative = v.at("mean_relative").get<double>();
      row.vertex.max_relative = v.at("max_relative").get<double>();
      row.vertex.vertices = v.at("vertices").get<std::size_t>();
      row.pareto = jr.value("pareto", false);
      // report_row_settings() must be able to rebuild the row's bake.
      if (row.bounces != "auto" && row.bounces != "inf") {
        std::size_t used = 0;
        int k = 0;
        try {
          k = std::stoi(row.bounces, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != row.bounces.size() || k < 1)
          throw Error(where, "row " + std::to_string(index) + ": bounces '" + row.bounces +
                                 "' is not auto, inf or a count");
      }
      d.rows.push_back(std::move(row));
      ++index;
    }
    d.seconds = j.value("seconds", 0.0);
  } catch (const json::exception& e) {
    throw Error(
        where, (d.rows.size() == index && j.contains("rows") ? "row " + std::to_string(index) + ": "
                                                             : std::string()) +
                   e.what());
  }
  return d;
}

ReportData read_report(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw Error(file.string(), "cannot open the report");
  json j;
  try {
    j = json::parse(in);
  } catch (const json::exception& e) {
    throw Error(file.string(), std::string("not valid JSON: ") + e.what());
  }
  return report_from_json(j, file.string());
}

}  // namespace bounce
