// `bounce report SCENE`: error against run time for every method and setting.
// The sweep itself is core (report/report_sweep.h: patch mode, patch count,
// bounces and codec, each measured against the path-traced reference); this
// command writes report.md and report.json, the plots (views/report_charts.h,
// when the studio's VTK is built and a display is available), and prints the
// table.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bounce/error.h"
#include "bounce/export.h"
#include "bounce/report.h"
#include "bounce/scene.h"
#include "commands.h"
#include "console_progress.h"
#ifdef BOUNCE_REPORT_CHARTS
#include "report_charts.h"
#endif

namespace bounce::cli {

namespace fs = std::filesystem;

namespace {

struct ReportOptions {
  std::string scene;
  std::string out;
  std::string cache;
  bool no_cache = false;
  bool quick = false;
  bool json = false;
  bool quiet = false;
  bool no_plots = false;
  ReportSweepSettings sweep;
};

std::string fixed(double v, int digits) {
  char s[64];
  std::snprintf(s, sizeof s, "%.*f", digits, v);
  return s;
}

std::string table(const std::vector<ReportRow>& rows) {
  std::ostringstream t;
  t << "| mode | patches | bounces | codec | bake s | update ms (direct + T b) | matrix KiB | "
       "compression: worst-light error | "
       "indirect rel. RMSE | full rel. RMSE | full PSNR dB | full SSIM | vertex rel. RMSE | "
       "layout error (picture / vertex) | mean level (picture / vertex) | Pareto |\n";
  t << "|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|:---:|\n";
  for (const ReportRow& r : rows) {
    t << "| " << r.mode << " | " << r.patches << " | " << r.bounces << " | " << r.codec << " | "
      << fixed(r.bake_seconds, 2) << " | " << fixed(r.update_ms(), 2) << " ("
      << fixed(r.direct_ms, 2) << " + " << fixed(r.multiply_ms, 3) << ") | "
      << fixed(static_cast<double>(r.matrix_bytes) / 1024.0, 1) << " | "
      << fixed(r.compression_light_error, 4) << " | " << fixed(r.indirect_error, 4) << " | "
      << fixed(r.full.relative_rmse, 4) << " | " << fixed(r.full.psnr, 2) << " | "
      << fixed(r.full.ssim, 4) << " | " << fixed(r.vertex_error, 4) << " | "
      << fixed(r.layout_indirect_error, 4) << " / " << fixed(r.layout_vertex_error, 4) << " | "
      << fixed(r.indirect_level, 3) << " / " << fixed(r.vertex_level, 3) << " | "
      << (r.pareto ? "*" : "") << " |\n";
  }
  return t.str();
}

// Virtual against voxel at the same target patch count (the paper's Table 3).
std::string comparison_table(const ReportData& report) {
  const std::vector<PatchModeComparison> pairs = compare_patch_modes(report);
  if (pairs.empty()) return {};
  std::ostringstream t;
  t << "Virtual patches against the voxel baseline at the same target patch count (dense "
       "matrix, auto bounces; errors are the indirect picture's relative RMSE, our target is a "
       "ratio <= 0.7; the paper's Table 3 reports MSE, 0.63 on its Cornell box, which is 0.80 "
       "as a ratio of RMSE). A layout error is the same row's error with exact patch values (the "
       "reference's light averaged over each patch, through the same gather): what the patch "
       "layout and the gather account for; a row well above its layout error loses the rest "
       "in the transport (form factors, visibility, bounces).\n\n";
  t << "| target | virtual patches | voxel patches | virtual error | voxel error | ratio | MSE "
       "ratio | virtual layout error | voxel layout error |\n";
  t << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const PatchModeComparison& c : pairs)
    t << "| " << c.patches_target << " | " << c.virtual_patches << " | " << c.voxel_patches << " | "
      << fixed(c.virtual_error, 4) << " | " << fixed(c.voxel_error, 4) << " | "
      << fixed(c.ratio(), 3) << " | " << fixed(c.mse_ratio(), 3) << " | "
      << fixed(c.virtual_layout_error, 4) << " | " << fixed(c.voxel_layout_error, 4) << " |\n";
  return t.str();
}

// The plots next to report.md; empty when they cannot be drawn, with `why`.
std::vector<fs::path> write_plots(const ReportData& report, const fs::path& out, std::string& why) {
#ifdef BOUNCE_REPORT_CHARTS
  // Debian 12's VTK 9.1 renders through X only (no EGL, no OSMesa): without
  // a display there is nothing to draw into.
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display) {
    why =
        "the plots need an X display (Debian's VTK 9.1 has no EGL or OSMesa): run under "
        "xvfb-run -a to get them";
    return {};
  }
  try {
    return views::write_report_charts(report, out);
  } catch (const Error& e) {
    // The numbers are measured: a plot that fails must not lose them.
    why = e.what();
    return {};
  }
#else
  (void)report;
  (void)out;
  why = "this build has no VTK (the studio was not built), so no plots";
  return {};
#endif
}

void run_report(ReportOptions opt) {
  opt.sweep.fill_defaults(opt.quick);
  opt.sweep.validate();

  Diagnostics diag;
  diag.set_listener([&opt](const Diagnostic& d) {
    if (d.kind == Diagnostic::Kind::Warning && !opt.quiet && !opt.json)
      std::fprintf(stderr, "bounce: warning: %s: %s\n", d.where.c_str(), d.message.c_str());
  });
  const Scene scene = SceneLoader(diag).load(opt.scene);
  ConsoleProgress console(opt.quiet || opt.json);
  std::unique_ptr<ReferenceCache> cache;
  if (!opt.no_cache)
    cache = std::make_unique<ReferenceCache>(opt.cache.empty() ? ReferenceCache::default_dir()
                                                               : fs::path(opt.cache));
  const bool chatty = !opt.quiet && !opt.json;
  const ReportData report = run_report_sweep(scene, opt.sweep, cache.get(), console.progress(),
                                             diag, [chatty](const std::string& line) {
                                               if (chatty)
                                                 std::fprintf(stderr, "report: %s\n", line.c_str());
                                             });

  const fs::path out = opt.out.empty() ? fs::path("reports") / scene.name : fs::path(opt.out);
  fs::create_directories(out);
  {
    AtomicFile f(out / "report.json");
    f.stream() << report_to_json(report).dump(2) << '\n';
    f.commit();
  }
  std::string no_plots_why;
  const std::vector<fs::path> plots =
      opt.no_plots ? std::vector<fs::path>{} : write_plots(report, out, no_plots_why);
  if (opt.no_plots) no_plots_why = "--no-plots";
  const std::string md_table = table(report.rows);
  const std::string md_comparison = comparison_table(report);
  {
    const ReportReference& ref = report.reference;
    AtomicFile f(out / "report.md");
    auto& s = f.stream();
    s << "# Error against run time: " << scene.name << "\n\n";
    s << "Reference: diffuse path tracer (docs/reference.md), " << ref.samples_per_pixel
      << " paths per pixel at " << ref.width << "x" << ref.height << ", " << ref.samples_per_vertex
      << " per vertex on " << ref.vertices << " evaluation vertices"
      << (ref.images_from_cache && ref.vertices_from_cache ? " (from the cache)" : "")
      << ". Its own noise, as a relative RMSE: full " << fixed(ref.noise_floor_full, 4)
      << ", indirect " << fixed(ref.noise_floor_indirect, 4)
      << " -- errors near these are at the reference's noise.\n\n";
    s << "Columns: bake s = the stages a standalone bake of the row runs; update ms = best of "
         "five light updates (direct light on the patches + the product T b); matrix KiB = "
         "the stored multi-bounce matrix; errors against the reference on the scene camera's "
         "pictures (background masked): indirect rel. RMSE with the reference's noise removed "
         "(docs/reference.md), full-picture relative RMSE, PSNR and SSIM as measured; vertex "
         "rel. RMSE = the indirect light at the evaluation vertices, noise removed. "
         "Pareto * = no other row has both lower indirect-image error and lower update time. "
         "Codecs are swept at `auto` bounces, other bounce counts use the dense matrix.\n\n";
    s << md_table << '\n';
    if (!md_comparison.empty()) s << md_comparison << '\n';
    if (!plots.empty()) {
      s << "## Plots\n\n";
      for (const fs::path& p : plots)
        s << "![" << p.stem().string() << "](" << p.filename().string() << ")\n\n";
    } else {
      s << "No plots: " << no_plots_why << ".\n";
    }
    f.commit();
  }
  // Said once, on stderr, so a table on stdout stays clean.
  if (plots.empty() && !opt.no_plots)
    std::fprintf(stderr, "bounce: report: no plots: %s\n", no_plots_why.c_str());
  if (opt.json) {
    std::cout << report_to_json(report).dump(2) << '\n';
    return;
  }
  std::printf("%s\n%s\nReport of %zu settings in %.1f s: %s, %s", md_table.c_str(),
              md_comparison.c_str(), report.rows.size(), report.seconds,
              (out / "report.md").string().c_str(), (out / "report.json").string().c_str());
  for (const fs::path& p : plots) std::printf(", %s", p.string().c_str());
  std::printf("\n");
}

}  // namespace

void register_report(CLI::App& app) {
  auto opt = std::make_shared<ReportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Error against run time: bake the scene over a sweep of settings (patch mode, patch count, "
      "bounces, codec) and measure each against a path-traced reference; writes report.md and "
      "report.json, PNG plots (error against run time with the Pareto front, against memory, "
      "virtual against voxel; they need an X display) and marks the Pareto front");
  cmd->add_option("scene", opt->scene, "Scene folder, scene.json or mesh file")->required();
  cmd->add_option("--out,-o", opt->out, "Output folder (default: reports/SCENE_NAME)");
  cmd->add_flag("--quick", opt->quick,
                "A small sweep (2 patch counts, small pictures, a noisier reference) for tests");
  cmd->add_option("--modes", opt->sweep.modes, "Patch modes: virtual, voxel (default both)");
  cmd->add_option("--patches", opt->sweep.patches,
                  "Target patch counts (default 150 300 600 1000; --quick: 60 150)");
  cmd->add_option("--bounces", opt->sweep.bounces, "Bounce settings (default 1 2 3 auto inf)");
  cmd->add_option("--codecs", opt->sweep.codecs,
                  "Codecs at auto bounces: dense, paper, ours, or NAME:KEPT_FRACTION (default "
                  "dense paper ours ours:0.02 ours:0.08)");
  cmd->add_option("--reference-samples", opt->sweep.reference_samples,
                  "Reference paths per pixel and per vertex (default 512; --quick: 128)");
  cmd->add_option("--width", opt->sweep.width, "Picture width (default 160; --quick: 64)");
  cmd->add_option("--height", opt->sweep.height, "Picture height (default 120; --quick: 48)");
  cmd->add_option("--transfer", opt->sweep.transfer,
                  "How patch light reaches pixels and vertices: final-gather (each point gathers "
                  "from the patches it sees through ray-traced form factors; default) or nearest "
                  "(a weighted mean of the patches around it)")
      ->check(CLI::IsMember({"final-gather", "nearest"}));
  cmd->add_option("--seed", opt->sweep.seed,
                  "Sampling seed of every bake (default 1, as bounce bake); run a few to see how "
                  "much one row depends on where the samples fell");
  cmd->add_option("--cache", opt->cache,
                  "Reference cache folder (default $XDG_CACHE_HOME/bounce/reference)");
  cmd->add_flag("--no-cache", opt->no_cache, "Always render the reference, store nothing");
  cmd->add_flag("--no-plots", opt->no_plots, "Write the table only, no PNG plots");
  cmd->add_flag("--json", opt->json, "Print report.json to stdout instead of the table");
  cmd->add_flag("--quiet,-q", opt->quiet, "No progress bars");
  cmd->callback([opt]() { run_report(*opt); });
}

}  // namespace bounce::cli
