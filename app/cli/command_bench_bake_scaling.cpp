// `bounce bench bake SCENE --scaling N1,N2,...`: the same bake at several
// patch counts, time and peak resident memory per stage (the manifest's stage
// statistics), the dense footprint the matrices would take in memory, and
// the exponent of each stage's growth with N fitted from the runs. With
// --extrapolate-to N the fitted exponents predict each stage's time at N,
// printed as a prediction, never as a measurement.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "bench_commands.h"
#include "bounce/bake.h"
#include "bounce/scene.h"
#include "commands.h"
#include "console_progress.h"

namespace bounce::cli {

namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

struct ScalingRun {
  int target = 0;
  std::size_t patches = 0;
  bool out_of_core = false;
  std::size_t dense_bytes = 0;  // F + the stored transport channels, float32
  std::vector<StageStats> stages;
  double total_seconds = 0.0;
};

// Least-squares slope of log(seconds) against log(patches): the exponent p in
// seconds ~ N^p. Runs whose stage took under 10 ms carry no signal and are
// left out; fewer than two points give no exponent (NaN).
double fitted_exponent(const std::vector<ScalingRun>& runs, const std::string& stage) {
  std::vector<std::pair<double, double>> points;
  for (const ScalingRun& r : runs)
    for (const StageStats& s : r.stages)
      if (s.name == stage && s.seconds >= 0.01 && r.patches > 0)
        points.emplace_back(std::log(static_cast<double>(r.patches)), std::log(s.seconds));
  if (points.size() < 2) return std::nan("");
  double mx = 0.0, my = 0.0;
  for (const auto& [x, y] : points) {
    mx += x;
    my += y;
  }
  mx /= static_cast<double>(points.size());
  my /= static_cast<double>(points.size());
  double sxy = 0.0, sxx = 0.0;
  for (const auto& [x, y] : points) {
    sxy += (x - mx) * (y - my);
    sxx += (x - mx) * (x - mx);
  }
  return sxx > 0.0 ? sxy / sxx : std::nan("");
}

}  // namespace

void run_bench_bake_scaling(const BakeOptions& opt, const std::vector<int>& sizes,
                            int extrapolate_to) {
  ConsoleProgress console(opt.quiet || opt.json);
  nlohmann::json all = nlohmann::json::array();
  for (const std::string& path : expand_globs(opt.scenes)) {
    Diagnostics load_diagnostics;
    const Scene scene = SceneLoader(load_diagnostics).load(path);
    std::vector<ScalingRun> runs;
    for (int target : sizes) {
      BakeSettings settings = opt.settings();
      settings.voxel_resolution.reset();
      settings.patches_total = target;
      Diagnostics diagnostics;
      const BakeResult r = Baker(scene, settings, diagnostics).run(console.progress());
      ScalingRun run;
      run.target = target;
      run.patches = r.patches.size();
      run.out_of_core = r.out_of_core.on;
      run.dense_bytes =
          (1 + r.transport.channels.size()) * run.patches * run.patches * sizeof(float);
      run.stages = r.stages;
      run.total_seconds = r.total_seconds;
      runs.push_back(run);
      if (!opt.json) {
        // Each run as soon as it ends: a long series shows its progress.
        std::printf("\n%s, N = %zu (target %d), out of core: %s; dense F + %zu T: %.2f GiB\n",
                    scene.name.c_str(), run.patches, target, run.out_of_core ? "yes" : "no",
                    r.transport.channels.size(), static_cast<double>(run.dense_bytes) / kGiB);
        std::printf("  %-24s %12s %16s %12s\n", "stage", "seconds", "peak RSS (GiB)",
                    "RSS / dense");
        for (const StageStats& s : run.stages)
          std::printf("  %-24s %11.2fs %16.3f %12.2f\n", s.name.c_str(), s.seconds,
                      static_cast<double>(s.peak_rss_bytes) / kGiB,
                      static_cast<double>(s.peak_rss_bytes) /
                          static_cast<double>(std::max<std::size_t>(run.dense_bytes, 1)));
        std::printf("  %-24s %11.2fs\n", "total", run.total_seconds);
        std::fflush(stdout);
      }
    }

    // Stages in the order of the first run; exponents over every run.
    std::vector<std::string> names;
    if (!runs.empty())
      for (const StageStats& s : runs.front().stages) names.push_back(s.name);
    std::map<std::string, double> exponent;
    for (const std::string& n : names) exponent[n] = fitted_exponent(runs, n);

    if (opt.json) {
      nlohmann::json j = {{"scene", scene.name}, {"runs", nlohmann::json::array()}};
      for (const ScalingRun& r : runs) {
        nlohmann::json stages = nlohmann::json::array();
        for (const StageStats& s : r.stages)
          stages.push_back(
              {{"name", s.name}, {"seconds", s.seconds}, {"peak_rss_bytes", s.peak_rss_bytes}});
        j["runs"].push_back({{"patches_target", r.target},
                             {"patches", r.patches},
                             {"out_of_core", r.out_of_core},
                             {"dense_bytes", r.dense_bytes},
                             {"stages", stages},
                             {"total_seconds", r.total_seconds}});
      }
      for (const std::string& n : names)
        j["exponents"][n] =
            std::isnan(exponent[n]) ? nlohmann::json() : nlohmann::json(exponent[n]);
      all.push_back(j);
      continue;
    }

    std::printf("\nscaling of %s: seconds per stage against N (peak RSS in GiB)\n",
                scene.name.c_str());
    std::printf("  %-24s", "stage \\ N");
    for (const ScalingRun& r : runs) std::printf(" %18zu", r.patches);
    std::printf(" %9s\n", "exponent");
    for (const std::string& n : names) {
      std::printf("  %-24s", n.c_str());
      for (const ScalingRun& r : runs) {
        const auto s = std::find_if(r.stages.begin(), r.stages.end(),
                                    [&](const StageStats& st) { return st.name == n; });
        if (s == r.stages.end()) {
          std::printf(" %18s", "-");
          continue;
        }
        char cell[64];
        std::snprintf(cell, sizeof cell, "%.1fs (%.2f)", s->seconds,
                      static_cast<double>(s->peak_rss_bytes) / kGiB);
        std::printf(" %18s", cell);
      }
      if (std::isnan(exponent[n]))
        std::printf(" %9s\n", "-");
      else
        std::printf(" %9.2f\n", exponent[n]);
    }
    std::printf("  %-24s", "dense F + T (GiB)");
    for (const ScalingRun& r : runs)
      std::printf(" %18.2f", static_cast<double>(r.dense_bytes) / kGiB);
    std::printf("\n");

    if (extrapolate_to > 0 && !runs.empty()) {
      const ScalingRun& last = runs.back();
      const double ratio = static_cast<double>(extrapolate_to) /
                           static_cast<double>(std::max<std::size_t>(last.patches, 1));
      std::printf("\nEXTRAPOLATED, not measured: N = %d from N = %zu with the exponents above\n",
                  extrapolate_to, last.patches);
      double total = 0.0;
      for (const StageStats& s : last.stages) {
        const double p = exponent[s.name];
        if (std::isnan(p)) {
          std::printf("  %-24s %12s\n", s.name.c_str(), "-");
          continue;
        }
        const double predicted = s.seconds * std::pow(ratio, p);
        total += predicted;
        std::printf("  %-24s %11.0fs  (N^%.2f)\n", s.name.c_str(), predicted, p);
      }
      std::printf("  %-24s %11.0fs\n", "total (predicted)", total);
    }
  }
  if (opt.json) std::cout << all.dump(2) << '\n';
}

}  // namespace bounce::cli
