// `bounce report SCENE`: error against run time for every method and setting.
// The sweep itself is core (report/report_sweep.h: patch mode, patch count,
// bounces and codec, each measured against the path-traced reference); this
// command writes report.md and report.json, the plots (views/report_charts.h,
// when the studio's VTK is built and a display is available), and prints the
// table. With several scenes (--scene A B ...) it writes one report folder
// per scene and one table comparing them (report_comparison.h).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <set>
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
#include "flag_spelling.h"
#include "number_text.h"
#include "report_comparison.h"
#ifdef BOUNCE_REPORT_CHARTS
#include "report_charts.h"
#endif

namespace bounce::cli {

namespace fs = std::filesystem;

namespace {

struct ReportOptions {
  std::string scene;
  std::vector<std::string> scenes;  // --scene: a batch when more than one in all
  std::string out;
  std::string cache;
  bool no_cache = false;
  bool quick = false;
  bool json = false;
  bool quiet = false;
  bool no_plots = false;
  ReportSweepSettings sweep;
};

std::string table(const std::vector<ReportRow>& rows) {
  std::ostringstream t;
  t << "| mode | patches | bounces | codec | bake s | update ms (direct + T b) | matrix KiB | "
       "compression: worst-light error | "
       "indirect rel. RMSE | full rel. RMSE | full PSNR dB | full SSIM | vertex rel. RMSE | "
       "layout error (picture / vertex) | mean level (picture / vertex) | "
       "probes rel. RMSE (level), count | Pareto |\n";
  t << "|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|:---:|\n";
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
      << (r.probe_level > 0.0 || r.probe_error > 0.0
              ? fixed(r.probe_error, 4) + " (" + fixed(r.probe_level, 3) + "), " +
                    std::to_string(r.probes)
              : std::string("-"))
      << " | " << (r.pareto ? "*" : "") << " |\n";
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

// Sweeps one scene and writes its report folder: `out`, or reports/NAME when
// empty; with `taken` (a batch), `out`/NAME, NAME-2, ... so that two scenes
// of one name keep both reports. Returns the report and the folder.
std::pair<ReportData, fs::path> report_one(const ReportOptions& opt, const std::string& scene_path,
                                           const fs::path& out_given, std::set<std::string>* taken,
                                           std::vector<fs::path>& plots, std::string& md_table,
                                           std::string& md_comparison) {
  Diagnostics diag;
  diag.set_listener([&opt](const Diagnostic& d) {
    if (d.kind == Diagnostic::Kind::Warning && !opt.quiet && !opt.json)
      std::fprintf(stderr, "bounce: warning: %s: %s\n", d.where.c_str(),
                   with_flag_spellings(d.message).c_str());
  });
  const Scene scene = SceneLoader(diag).load(scene_path);
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

  fs::path out = out_given.empty() ? fs::path("reports") / scene.name : out_given;
  if (taken) {
    std::string name = scene.name;
    for (int k = 2; !taken->insert(name).second; ++k) name = scene.name + "-" + std::to_string(k);
    out = out_given / name;
  }
  fs::create_directories(out);
  {
    AtomicFile f(out / "report.json");
    f.stream() << report_to_json(report).dump(2) << '\n';
    f.commit();
  }
  std::string no_plots_why;
  plots = opt.no_plots ? std::vector<fs::path>{} : write_plots(report, out, no_plots_why);
  if (opt.no_plots) no_plots_why = "--no-plots";
  md_table = table(report.rows);
  md_comparison = comparison_table(report);
  {
    const ReportReference& ref = report.reference;
    AtomicFile f(out / "report.md");
    auto& s = f.stream();
    s << "# Error against run time: " << scene.name << "\n\n";
    s << "Reference: diffuse path tracer (docs/reference.md), " << ref.samples_per_pixel
      << " paths per pixel at " << ref.width << "x" << ref.height << ", " << ref.samples_per_vertex
      << " per vertex on " << ref.vertices
      << " evaluation vertices (each measured 5% of the way into a face that uses it, where "
         "the final gather gathers for it: on the vertex itself it lies in its neighbours' planes)"
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
  return {report, out};
}

// Several scenes: a report folder each under `out` (reports/ when empty),
// then the comparison table (comparison.md, comparison.json in `out`). A
// failing scene does not stop the others; exit 2 when some failed, 1 when
// all did.
void run_report_batch(const ReportOptions& opt, const std::vector<std::string>& paths) {
  const fs::path root = opt.out.empty() ? fs::path("reports") : fs::path(opt.out);
  std::vector<ReportOfScene> scenes;
  std::set<std::string> taken;
  for (const std::string& path : paths) {
    ReportOfScene s;
    s.scene = path;
    try {
      std::vector<fs::path> plots;
      std::string md_table, md_comparison;
      auto [report, out] = report_one(opt, path, root, &taken, plots, md_table, md_comparison);
      s.report = std::move(report);
      s.out = out.string();
      s.ok = true;
      if (!opt.quiet && !opt.json)
        std::fprintf(stderr, "report: %s: %zu settings in %.1f s, %s\n", path.c_str(),
                     s.report.rows.size(), s.report.seconds, s.out.c_str());
    } catch (const Cancelled&) {
      throw;
    } catch (const std::exception& e) {
      s.error = e.what();
      std::fprintf(stderr, "bounce: error: %s\n", e.what());
    }
    scenes.push_back(std::move(s));
  }
  std::size_t failed = 0;
  for (const ReportOfScene& s : scenes) failed += s.ok ? 0 : 1;
  const std::string md = report_comparison_table(scenes);
  fs::create_directories(root);
  {
    AtomicFile f(root / "comparison.json");
    f.stream() << report_comparison_json(scenes).dump(2) << '\n';
    f.commit();
  }
  {
    AtomicFile f(root / "comparison.md");
    auto& s = f.stream();
    s << "# Error against run time: " << scenes.size() - failed << " scenes\n\n";
    s << "Each scene's full report is in its folder. Columns: patches = what the bake made; "
         "update ms = best of five light updates (direct light + T b); compression: worst-light "
         "error = the compressed matrix's relative RMS error of the indirect light on the worst "
         "evaluation light, against the exact matrix (0: dense); indirect rel. RMSE = the "
         "indirect picture against the path-traced reference, its noise removed; Pareto * = no "
         "other row of the same scene has both lower indirect error and lower update time.\n\n";
    s << md << '\n';
    for (const ReportOfScene& r : scenes)
      if (!r.ok) s << "Failed: " << r.scene << ": " << r.error << "\n\n";
    f.commit();
  }
  if (opt.json) {
    std::cout << report_comparison_json(scenes).dump(2) << '\n';
  } else {
    std::printf("%s\n%zu of %zu scenes reported: %s, %s\n", md.c_str(), scenes.size() - failed,
                scenes.size(), (root / "comparison.md").string().c_str(),
                (root / "comparison.json").string().c_str());
  }
  if (failed > 0) throw ExitCode{failed == scenes.size() ? 1 : 2};
}

// The core names a sweep setting by its field (reference_samples,
// width/height); the user typed its option (--reference-samples,
// --width/--height).
void validate_sweep(const ReportSweepSettings& sweep) {
  try {
    sweep.validate();
  } catch (const Error& e) {
    std::string flags = "--" + e.where();
    for (std::size_t i = 0; i < flags.size(); ++i) {
      if (flags[i] == '_') flags[i] = '-';
      if (flags[i] == '/') flags.insert(i + 1, "--");
    }
    throw Error(flags, std::string(e.what()).substr(e.where().size() + 2));
  }
}

void run_report(ReportOptions opt) {
  opt.sweep.fill_defaults(opt.quick);
  validate_sweep(opt.sweep);
  std::vector<std::string> paths;
  if (!opt.scene.empty()) paths.push_back(opt.scene);
  for (const std::string& p : expand_globs(opt.scenes)) paths.push_back(p);
  if (paths.empty()) throw Error("report", "no scene: give SCENE or --scene SCENE ...");
  if (paths.size() > 1) {
    run_report_batch(opt, paths);
    return;
  }
  std::vector<fs::path> plots;
  std::string md_table, md_comparison;
  const auto [report, out] =
      report_one(opt, paths[0], fs::path(opt.out), nullptr, plots, md_table, md_comparison);
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
  cmd->add_option("scene", opt->scene, "Scene folder, scene.json or mesh file");
  cmd->add_option("--scene", opt->scenes,
                  "Scenes to report on (repeatable, or several after one --scene, quoted globs "
                  "allowed), with SCENE if given. Two or more: a report folder per scene in "
                  "--out (default reports/) and one table comparing them, comparison.md and "
                  "comparison.json there; a failing scene does not stop the others (exit 2, 1 "
                  "when all failed)");
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
  cmd->add_flag("--no-light-probes{false}", opt->sweep.light_probes,
                "Leave out the light probes' column (by default every row is baked with light "
                "probes, and their SH, blended at up to 64 points of the empty space, is "
                "measured against the reference's indirect irradiance there for the six axis "
                "normals)");
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
