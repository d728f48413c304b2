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

static std::string number_or_text(const json& v, const char* fmt) {
  if (v.is_string()) return v.get<std::string>();
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v.get<double>());
  return buf;
}

void print_transport_report(std::FILE* out, const json& m) {
  if (!m.contains("transport")) return;
  const json& t = m["transport"];
  std::fprintf(out, "\nTransport (%zu patches, %s)\n", t["patches"].get<std::size_t>(),
               t["backend"].get<std::string>().c_str());
  for (const json& c : t["channels"]) {
    std::fprintf(out,
                 "  %-3s K = %-4s %-12s %-8s spectral radius %.4f  truncation bound %s  "
                 "condition %s  %.2fs\n",
                 c["rgb"].get<std::string>().c_str(), number_or_text(c["bounces"], "%g").c_str(),
                 c["method"].get<std::string>().c_str(), c["precision"].get<std::string>().c_str(),
                 c["spectral_radius"].get<double>(),
                 number_or_text(c["truncation_bound"], "%.2e").c_str(),
                 number_or_text(c["condition_number"], "%.3g").c_str(), c["seconds"].get<double>());
  }
  for (const json& d : t["decisions"])
    std::fprintf(out, "  - %s: %s\n", d["what"].get<std::string>().c_str(),
                 d["why"].get<std::string>().c_str());

  const json& c = m["compression"];
  const json& sz = c["sizes"];
  std::fprintf(out, "\nStorage: %s, %.2f MiB (dense float RGB %.2f MiB, ratio %.1fx)\n",
               c["codec"].get<std::string>().c_str(), mib(sz["stored_bytes"]),
               mib(sz["dense_rgb_float32_bytes"]), sz["ratio_to_dense_rgb"].get<double>());
  for (const json& d : c["decisions"])
    std::fprintf(out, "  - %s: %s\n", d["what"].get<std::string>().c_str(),
                 d["why"].get<std::string>().c_str());
  if (!c.contains("errors")) return;
  std::fprintf(out,
               "  parts        kept %.2f MiB (%g of the entries, %s), blocks %.2f MiB, permutation "
               "%.2f MiB\n",
               mib(sz["sparse_bytes"]), c.value("kept_fraction", 0.0),
               c.value("kept_storage", "float32").c_str(), mib(sz["block_bytes"]),
               mib(sz["permutation_bytes"]));
  const json& e = c["errors"];
  std::fprintf(out, "  |error|      mean %.3e  max %.3e  sum %.4g  (relative Frobenius %.3e)\n",
               e["mean_abs"].get<double>(), e["max_abs"].get<double>(), e["sum_abs"].get<double>(),
               e["rel_frobenius"].get<double>());
  const json& li = e["indirect_light"];
  std::fprintf(out, "  indirect     relative RMS error mean %.3e, max %.3e over %zu lights\n",
               li["rel_rms_mean"].get<double>(), li["rel_rms_max"].get<double>(),
               li["lights"].get<std::size_t>());
}

void print_bake_report(std::FILE* out, const json& m) {
  const json& c = m["counts"];
  const json& s = m["settings"]["resolved"];
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
  std::fprintf(out,
               "  area        %.4g sampled of %.4g surface (%.4g by %zu samples at part centres)\n",
               sa["sampled_area"].get<double>(), sa["surface_area"].get<double>(),
               sa["centre_sampled_area"].get<double>(), sa["centre_samples"].get<std::size_t>());
  const json& f = m["checks"]["form_factors"];
  std::fprintf(out, "\nForm-factor checks\n");
  std::fprintf(out, "  row sums     max %.4f  mean %.4f  rows > 1: %zu\n",
               f["row_sum_max"].get<double>(), f["row_sum_mean"].get<double>(),
               f["rows_above_one"].get<std::size_t>());
  std::fprintf(out, "  largest F    %.4f\n", f["value_max"].get<double>());
  std::fprintf(out, "  reciprocity  worst row %.2e, whole matrix %.2e (unreciprocated share)\n",
               f["reciprocity_error_max"].get<double>(), f["reciprocity_error_rel"].get<double>());
  std::fprintf(out, "  NaN/Inf      %zu\n", f["non_finite"].get<std::size_t>());
  print_transport_report(out, m);
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
      std::fprintf(out, "  %-28s %10.2f MiB\n", e["name"].get<std::string>().c_str(),
                   mib(e["bytes"]));
  }
}

}  // namespace bounce::cli
