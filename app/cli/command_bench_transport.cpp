// `bounce bench transport`: how fast one n x n float32 product is on each
// backend of the transport stage, with an unblocked loop as the naive
// baseline, measured back to back in one process (timings swing +-30% run to
// run on the shared machine: the ratios are the figures to compare).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench_commands.h"
#include "bounce/error.h"
#include "transport_bench.h"

namespace bounce::cli {

namespace {

struct TransportBenchOptions {
  std::vector<std::size_t> sizes = {512, 1024, 2048};
  int repeats = 3;
  bool lu = false;
  bool no_plain = false;
  bool json = false;
  bool quiet = false;
};

// Best time of the OpenBLAS product: the reference of every ratio.
double openblas_seconds(const TransportBench& b) {
  for (const BenchEntry& e : b.entries)
    if (e.available && e.what.rfind("OpenBLAS", 0) == 0) return e.timing.best_seconds;
  return 0.0;
}

void print_table(const TransportBench& b) {
  const double reference = openblas_seconds(b);
  std::size_t width = 8;
  for (const BenchEntry& e : b.entries) width = std::max(width, e.what.size());
  const int w = static_cast<int>(width);
  std::printf(
      "\nbench transport: n = %zu, float32, best and median of the runs after one "
      "warm-up\n",
      b.n);
  std::printf(
      "  (ratio = best time / OpenBLAS sgemm's best time; solve GFLOP/s count the solve's own "
      "flops: "
      "Cholesky 7/3 n^3, LU 8/3 n^3)\n");
  std::printf("  %-*s %5s %12s %12s %10s %9s\n", w, "what", "runs", "best (s)", "median (s)",
              "GFLOP/s", "ratio");
  for (const BenchEntry& e : b.entries) {
    if (!e.available) {
      std::printf("  %-*s not run: %s\n", w, e.what.c_str(), e.error.c_str());
      continue;
    }
    const GemmTiming& t = e.timing;
    std::printf("  %-*s %5d %12.4f %12.4f %10.1f %8.2fx\n", w, e.what.c_str(), t.repeats,
                t.best_seconds, t.median_seconds, t.gflops,
                reference > 0.0 ? t.best_seconds / reference : 0.0);
  }
}

nlohmann::json to_json(const TransportBench& b) {
  const double reference = openblas_seconds(b);
  nlohmann::json entries = nlohmann::json::array();
  for (const BenchEntry& e : b.entries) {
    nlohmann::json j = {{"what", e.what}, {"available", e.available}};
    if (!e.available) {
      j["error"] = e.error;
    } else {
      j["runs"] = e.timing.repeats;
      j["best_seconds"] = e.timing.best_seconds;
      j["median_seconds"] = e.timing.median_seconds;
      j["gflops"] = e.timing.gflops;
      j["ratio_to_openblas"] = reference > 0.0 ? e.timing.best_seconds / reference : 0.0;
    }
    entries.push_back(j);
  }
  return {{"n", b.n}, {"repeats", b.repeats}, {"entries", entries}};
}

void run(const TransportBenchOptions& opt) {
  for (std::size_t n : opt.sizes)
    if (n == 0 || n > 32768)
      throw Error("--n", "sizes must be between 1 and 32768, got " + std::to_string(n));
  if (opt.repeats < 1 || opt.repeats > 100)
    throw Error("--repeats", "must be between 1 and 100, got " + std::to_string(opt.repeats));
  nlohmann::json all = nlohmann::json::array();
  for (std::size_t n : opt.sizes) {
    if (!opt.quiet && !opt.json)
      std::fprintf(stderr, "  timing n = %zu: OpenBLAS, CLBlast%s%s ...\n", n,
                   opt.no_plain ? "" : ", plain loop",
                   opt.lu ? ", Cholesky and LU in float32 and float64" : "");
    const TransportBench b = run_transport_bench(n, opt.repeats, opt.lu, !opt.no_plain);
    if (opt.json) {
      all.push_back(to_json(b));
    } else {
      print_table(b);
      std::fflush(stdout);
    }
  }
  if (opt.json) std::cout << all.dump(2) << '\n';
}

}  // namespace

void register_bench_transport(CLI::App& bench) {
  auto opt = std::make_shared<TransportBenchOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "transport",
      "Time one n x n float32 matrix product on OpenBLAS, CLBlast and a plain loop (and LU)");
  cmd->footer(
      "The product is the transport stage's building block. Per size, one table: best and "
      "median seconds, GFLOP/s (2 n^3 flops per product) and the time relative to OpenBLAS. "
      "CLBlast runs on OpenCL (PoCL's CPU device here, no GPU). The plain baseline is an "
      "OpenMP-parallel i-k-j triple loop without cache blocking. Timings swing +-30% run to run "
      "on a shared machine: compare the ratios within one run.\n\nExample:\n  bounce bench "
      "transport --n 512,1024,2048 --lu");
  cmd->add_option("--n", opt->sizes,
                  "Matrix sizes, comma-separated. The plain loop runs once (no warm-up) at "
                  "n = 2048 and is skipped above it")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--repeats", opt->repeats,
                  "Timed runs per backend and size, after one untimed warm-up; best and median "
                  "are reported")
      ->capture_default_str();
  cmd->add_flag("--lu", opt->lu,
                "Also time the K = infinity solve (I - M) T = M by Cholesky and by LU, in float32 "
                "and float64, on one random balanced M");
  cmd->add_flag("--no-plain", opt->no_plain, "Leave out the plain triple-loop baseline");
  cmd->add_flag("--json", opt->json, "Print the timings as JSON on stdout instead of tables");
  cmd->add_flag("--quiet,-q", opt->quiet, "No progress lines on stderr");
  cmd->callback([opt]() { run(*opt); });
}

}  // namespace bounce::cli
