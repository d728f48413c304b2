#include "report_comparison.h"

#include <set>
#include <sstream>

#include "number_text.h"

namespace bounce::cli {

std::string report_comparison_table(const std::vector<ReportOfScene>& scenes) {
  std::ostringstream t;
  t << "| scene | patches | mode | bounces | codec | update ms | matrix KiB | compression: "
       "worst-light error | indirect rel. RMSE | Pareto |\n";
  t << "|---|---:|---|---|---|---:|---:|---:|---:|:---:|\n";
  for (const ReportOfScene& s : scenes) {
    if (!s.ok) continue;
    for (const ReportRow& r : s.report.rows)
      t << "| " << s.report.scene_name << " | " << r.patches << " | " << r.mode << " | "
        << r.bounces << " | " << r.codec << " | " << fixed(r.update_ms(), 3) << " | "
        << fixed(static_cast<double>(r.matrix_bytes) / 1024.0, 1) << " | "
        << fixed(r.compression_light_error, 4) << " | " << fixed(r.indirect_error, 4) << " | "
        << (r.pareto ? "*" : "") << " |\n";
  }
  return t.str();
}

nlohmann::ordered_json report_comparison_json(const std::vector<ReportOfScene>& scenes) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  std::size_t failed = 0;
  for (const ReportOfScene& s : scenes) {
    nlohmann::ordered_json j;
    j["scene"] = s.scene;
    j["ok"] = s.ok;
    if (!s.ok) {
      ++failed;
      j["error"] = s.error;
      list.push_back(std::move(j));
      continue;
    }
    j["name"] = s.report.scene_name;
    j["out"] = s.out;
    std::set<std::size_t> patch_counts;
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const ReportRow& r : s.report.rows) {
      patch_counts.insert(r.patches);
      rows.push_back({{"patches", r.patches},
                      {"mode", r.mode},
                      {"bounces", r.bounces},
                      {"codec", r.codec},
                      {"update_ms", r.update_ms()},
                      {"matrix_bytes", r.matrix_bytes},
                      {"compression_light_rel_rms_max", r.compression_light_error},
                      {"image_indirect_noise_corrected_relative_rmse", r.indirect_error},
                      {"pareto", r.pareto}});
    }
    j["patches"] = patch_counts;
    j["rows"] = std::move(rows);
    list.push_back(std::move(j));
  }
  return {{"scenes", std::move(list)}, {"failed", failed}};
}

}  // namespace bounce::cli
