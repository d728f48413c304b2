#include "bake_report.h"

#include <string>

namespace bounce::cli {

using nlohmann::json;

static double mib(const json& bytes) { return bytes.get<double>() / (1024.0 * 1024.0); }

void print_stage_table(std::FILE* out, const json& m) {
  std::fprintf(out, "  %-26s %10s %14s\n", "stage", "time (s)", "peak RSS (MiB)");
  for (const json& s : m["stages"])
    std::fprintf(out, "  %-26s %10.3f %14.1f\n", s["name"].get<std::string>().c_str(),
                 s["seconds"].get<double>(), mib(s["peak_rss_bytes"]));
  std::fprintf(out, "  %-26s %10.3f\n", "total", m["total_seconds"].get<double>());
}

void print_bake_report(std::FILE* out, const json& m) {
  const json& c = m["counts"];
  const json& s = m["settings"];
  const json& g = m["grid"];
  std::fprintf(out, "\nBake of '%s' (%s patches)\n", m["scene"]["name"].get<std::string>().c_str(),
               s["patch_mode"].get<std::string>().c_str());
  std::fprintf(out, "  grid        %d x %d x %d cells of %.4g (resolution %d)\n",
               g["dims"][0].get<int>(), g["dims"][1].get<int>(), g["dims"][2].get<int>(),
               g["cell_size"].get<double>(), s["voxel_resolution"].get<int>());
  std::fprintf(out, "  triangles   %zu\n", c["triangles"].get<std::size_t>());
  std::fprintf(out, "  voxels      %zu occupied of %zu\n", c["occupied_voxels"].get<std::size_t>(),
               c["grid_cells"].get<std::size_t>());
  std::fprintf(out, "  samples     %zu\n", c["samples"].get<std::size_t>());
  std::fprintf(out, "  patches     %zu (%zu before leaving out patches that see nothing)\n",
               c["patches"].get<std::size_t>(), c["patches_before_pruning"].get<std::size_t>());
  const json& sa = m["sampling"];
  std::fprintf(out, "  area        %.4g sampled of %.4g surface (%.4g unsampled)\n",
               sa["sampled_area"].get<double>(), sa["surface_area"].get<double>(),
               sa["unsampled_area"].get<double>());
  const json& f = m["checks"]["form_factors"];
  std::fprintf(out, "\nForm-factor checks\n");
  std::fprintf(out, "  row sums     max %.4f  mean %.4f  rows > 1: %zu\n",
               f["row_sum_max"].get<double>(), f["row_sum_mean"].get<double>(),
               f["rows_above_one"].get<std::size_t>());
  std::fprintf(out, "  largest F    %.4f\n", f["value_max"].get<double>());
  std::fprintf(out, "  reciprocity  worst row %.2e, whole matrix %.2e (unreciprocated share)\n",
               f["reciprocity_error_max"].get<double>(), f["reciprocity_error_rel"].get<double>());
  std::fprintf(out, "  NaN/Inf      %zu\n", f["non_finite"].get<std::size_t>());
  std::fprintf(out, "\nStages\n");
  print_stage_table(out, m);
  if (!m["left_out"].empty()) {
    std::fprintf(out, "\nLeft out\n");
    for (const json& e : m["left_out"])
      std::fprintf(out, "  - %s: %s\n", e["where"].get<std::string>().c_str(),
                   e["message"].get<std::string>().c_str());
  }
  if (!m["warnings"].empty()) {
    std::fprintf(out, "\nWarnings\n");
    for (const json& e : m["warnings"])
      std::fprintf(out, "  - %s: %s\n", e["where"].get<std::string>().c_str(),
                   e["message"].get<std::string>().c_str());
  }
  if (m.contains("files")) {
    std::fprintf(out, "\nFiles\n");
    for (const json& e : m["files"])
      std::fprintf(out, "  %-14s %10.2f MiB\n", e["name"].get<std::string>().c_str(),
                   mib(e["bytes"]));
  }
}

}  // namespace bounce::cli
