#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>

#include "bake_report.h"
#include "bench_commands.h"
#include "bounce/bake.h"
#include "bounce/scene.h"
#include "commands.h"
#include "console_progress.h"
#include "transport_bench.h"

namespace bounce::cli {

namespace {

// The transport stage's rate against OpenBLAS sgemm at the bake's n, measured
// in the same run: how close the stage gets to the machine's dense speed.
struct TransportRate {
  double gflop = 0.0;
  double seconds = 0.0;
  double gflops = 0.0;
  double sgemm_gflops = 0.0;
  std::string methods;
};

TransportRate transport_rate(const BakeResult& r) {
  TransportRate t;
  t.gflop = r.transport.flops * 1e-9;
  t.seconds = r.transport.seconds;
  t.gflops = t.seconds > 0.0 ? t.gflop / t.seconds : 0.0;
  for (const ChannelTransport& c : r.transport.channels)
    t.methods += (t.methods.empty() ? "" : ", ") + c.method;
  if (r.transport.n > 0) t.sgemm_gflops = time_openblas_sgemm(r.transport.n, 3).gflops;
  return t;
}

void print_transport_rate(const TransportRate& t, std::size_t n) {
  std::printf(
      "  transport: %.1f GFLOP in %.3f s = %.1f GFLOP/s (%s); OpenBLAS sgemm %zux%zu "
      "(best of 3, this run): %.1f GFLOP/s; transport at %.0f%% of sgemm\n",
      t.gflop, t.seconds, t.gflops, t.methods.c_str(), n, n, t.sgemm_gflops,
      t.sgemm_gflops > 0.0 ? 100.0 * t.gflops / t.sgemm_gflops : 0.0);
}

void run_bench_bake(const BakeOptions& opt) {
  ConsoleProgress console(opt.quiet || opt.json);
  nlohmann::json all = nlohmann::json::array();
  for (const std::string& path : expand_globs(opt.scenes)) {
    Diagnostics diagnostics;
    const Scene scene = SceneLoader(diagnostics).load(path);
    const BakeResult ours = Baker(scene, opt.settings(), diagnostics).run(console.progress());
    const nlohmann::json m = make_manifest(scene, ours, diagnostics);
    // Baseline in the same run: the other patch mode on the same grid (the
    // voxel approximation of the published method when we bake virtual patches).
    BakeSettings other = ours.settings;
    other.patch_mode =
        ours.settings.patch_mode == PatchMode::Virtual ? PatchMode::Voxel : PatchMode::Virtual;
    Diagnostics baseline_diagnostics;
    const BakeResult base = Baker(scene, other, baseline_diagnostics).run(console.progress());
    const nlohmann::json b = make_manifest(scene, base, baseline_diagnostics);
    const TransportRate rate = transport_rate(ours);
    if (opt.json) {
      all.push_back({{"scene", scene.name},
                     {"settings", m["settings"]},
                     {"counts", m["counts"]},
                     {"stages", m["stages"]},
                     {"total_seconds", m["total_seconds"]},
                     {"transport_rate",
                      {{"gflop", rate.gflop},
                       {"seconds", rate.seconds},
                       {"gflops", rate.gflops},
                       {"sgemm_gflops", rate.sgemm_gflops},
                       {"methods", rate.methods}}},
                     {"baseline",
                      {{"settings", b["settings"]},
                       {"counts", b["counts"]},
                       {"stages", b["stages"]},
                       {"total_seconds", b["total_seconds"]}}}});
      continue;
    }
    std::printf("\nbench bake: %s, %zu triangles, grid %d, %d x %d rays per voxel face\n",
                scene.name.c_str(), scene.triangle_count(),
                ours.settings.voxel_resolution.value_or(0), *ours.settings.samples_per_face,
                *ours.settings.samples_per_face);
    std::printf("  (ratio = first column / second; peak RSS of the first)\n");
    std::printf("  %-24s %14s %14s %14s %8s\n", "stage",
                to_string(ours.settings.patch_mode).c_str(), to_string(other.patch_mode).c_str(),
                "peak RSS (MiB)", "ratio");
    for (std::size_t k = 0; k < ours.stages.size() && k < base.stages.size(); ++k) {
      const double a = ours.stages[k].seconds, c = base.stages[k].seconds;
      char ratio[32] = "-";
      if (c > 1e-3) std::snprintf(ratio, sizeof ratio, "%.2fx", a / c);
      std::printf("  %-24s %13.3fs %13.3fs %14.1f %8s\n", ours.stages[k].name.c_str(), a, c,
                  static_cast<double>(ours.stages[k].peak_rss_bytes) / (1024.0 * 1024.0), ratio);
    }
    std::printf("  %-24s %13.3fs %13.3fs %14s %7.2fx\n", "total", ours.total_seconds,
                base.total_seconds, "", ours.total_seconds / std::max(1e-9, base.total_seconds));
    std::printf("  %-24s %14zu %14zu\n", "patches", ours.patches.size(), base.patches.size());
    std::printf("  %-24s %14zu %14zu\n", "samples", ours.samples.samples.size(),
                base.samples.samples.size());
    std::printf("  %-24s %14.4f %14.4f\n", "row sum max", ours.checks.row_sum_max,
                base.checks.row_sum_max);
    std::printf("  %-24s %14.2e %14.2e\n", "reciprocity (matrix)",
                ours.checks.reciprocity_error_rel, base.checks.reciprocity_error_rel);
    print_transport_rate(rate, ours.transport.n);
  }
  if (opt.json) std::cout << all.dump(2) << '\n';
}

}  // namespace

void register_bench(CLI::App& app) {
  CLI::App* bench = app.add_subcommand(
      "bench",
      "Benchmarks: time and memory of each stage, with baselines measured in the same run");
  bench->require_subcommand(1);
  auto opt = std::make_shared<BakeOptions>();
  auto scaling = std::make_shared<std::vector<int>>();
  auto extrapolate_to = std::make_shared<int>(0);
  CLI::App* bake =
      bench->add_subcommand("bake", "Time and peak memory per bake stage (nothing is written)");
  opt->add_to(*bake, false);
  CLI::Option* scaling_option =
      bake->add_option("--scaling", *scaling,
                       "Bake at each of these patch counts (e.g. 4096,8192,16384; overrides "
                       "--voxel/--patches-total, no voxel baseline) and print time and peak "
                       "memory per stage against N with each stage's fitted exponent")
          ->delimiter(',')
          ->check(CLI::Range(1, 1 << 20));
  bake->add_option("--extrapolate-to", *extrapolate_to,
                   "With --scaling: predict each stage's time at this N from the fitted "
                   "exponents (printed as a prediction, not a measurement)")
      ->needs(scaling_option)
      ->check(CLI::Range(1, 1 << 20));
  bake->callback([opt, scaling, extrapolate_to]() {
    if (scaling->empty())
      run_bench_bake(*opt);
    else
      run_bench_bake_scaling(*opt, *scaling, *extrapolate_to);
  });
  register_bench_transport(*bench);
  register_bench_compress(*bench);
  register_bench_ordering(*bench);
  register_bench_runtime(*bench);
  register_bench_dynamic(*bench);
}

}  // namespace bounce::cli
