#pragma once
// `bounce report` over several scenes: one table comparing them, a row per
// scene and swept setting (patch count, mode, bounces, codec) with the
// compression's worst-light error, the indirect error against the reference
// and the update time, and each scene's Pareto front (no other row of the
// same scene has both lower indirect error and lower update time).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bounce/report.h"

namespace bounce::cli {

// One scene of the batch: its report, or why it has none.
struct ReportOfScene {
  std::string scene;  // as given on the command line
  std::string out;    // its report folder
  bool ok = false;
  std::string error;
  ReportData report;
};

// The Markdown table of every successful scene's rows, scene after scene.
std::string report_comparison_table(const std::vector<ReportOfScene>& scenes);
// The same as JSON: {"scenes": [{scene, name, out, ok, error, patches: [...],
// rows: [...]}], "failed": k}.
nlohmann::ordered_json report_comparison_json(const std::vector<ReportOfScene>& scenes);

}  // namespace bounce::cli
