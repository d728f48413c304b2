// `bounce bench runtime BAKE`: milliseconds per light update of every way to
// compute the indirect light T b of a compressed bake (OpenCL, C++), against
// the dense float32 matrix (when the bake holds T.npy) and the classic K
// iterations on the form factors (when it holds F.npy), with bytes read per
// update, effective bandwidth and the machine's own read bandwidth measured
// in the same run.
#include <cstdio>
#include <iostream>
#include <memory>

#include "bench_commands.h"
#include "bounce/bake_folder.h"
#include "bounce/error.h"
#include "runtime_bench.h"

namespace bounce::cli {

namespace {

struct RuntimeBenchOptions {
  std::string bake;
  int repeats = 20;
  int bounces = 0;  // classic K; 0 = the bake's
  bool json = false;
};

// K for the classic baseline: the bake's K, or where its auto series
// converged when it computed K = infinity.
int bake_bounces(const LoadedBake& bake) {
  return bake.description.bounces > 0 ? bake.description.bounces : 16;
}

void run(const RuntimeBenchOptions& opt) {
  if (opt.repeats < 1 || opt.repeats > 10000)
    throw Error("--repeats", "must be between 1 and 10000");
  const LoadedBake b = BakeReader::read(opt.bake, true);
  if (!b.compressed)
    throw Error(opt.bake, "holds no compressed matrix (T.dds): bake with --codec ours or paper");
  std::vector<const float*> dense;
  for (const auto& t : b.dense) dense.push_back(t.data());
  std::unique_ptr<ClassicRadiosity> classic;
  const int k = opt.bounces > 0 ? opt.bounces : bake_bounces(b);
  if (std::optional<std::vector<float>> f = read_form_factors(opt.bake, b.size())) {
    std::vector<glm::vec3> albedo;
    for (const Patch& p : b.patches.patches) albedo.push_back(p.albedo);
    classic = std::make_unique<ClassicRadiosity>(std::move(*f), std::move(albedo), k);
  }
  const std::optional<FinalGather> gather =
      read_final_gather(opt.bake, b.size(), b.samples.samples.size());
  const RuntimeBench bench = run_runtime_bench(*b.compressed, b.channel_of_rgb, dense, opt.repeats,
                                               classic.get(), gather ? &*gather : nullptr);
  if (opt.json) {
    nlohmann::json entries = nlohmann::json::array();
    for (const RuntimeBenchEntry& e : bench.entries)
      entries.push_back({{"what", e.what},
                         {"available", e.available},
                         {"default_loop", e.default_loop},
                         {"error", e.error},
                         {"best_ms", e.best_ms},
                         {"median_ms", e.median_ms},
                         {"bytes", e.bytes},
                         {"gb_per_s", e.gb_per_s},
                         {"max_rel_diff", e.max_rel_diff}});
    nlohmann::json final_gather = nullptr;
    nlohmann::json gather_loops = nlohmann::json::array();
    for (const RuntimeBenchEntry& e : bench.gather_loops)
      gather_loops.push_back({{"what", e.what},
                              {"chosen", e.default_loop},
                              {"best_ms", e.best_ms},
                              {"median_ms", e.median_ms},
                              {"max_rel_diff", e.max_rel_diff}});
    if (bench.gather.available)
      final_gather = {{"vertices", bench.gather_points},
                      {"loops", gather_loops},
                      {"entries", bench.gather_entries},
                      {"entry_bytes", bench.gather_compact ? 4 : 8},
                      {"best_ms", bench.gather.best_ms},
                      {"median_ms", bench.gather.median_ms},
                      {"bytes", bench.gather.bytes},
                      {"gb_per_s", bench.gather.gb_per_s},
                      {"max_rel_diff", bench.gather.max_rel_diff}};
    std::cout << nlohmann::json{{"bake", opt.bake},
                                {"patches", bench.n},
                                {"stored_channels", bench.channels},
                                {"format", bench.format},
                                {"read_bandwidth_gb_per_s", bench.stream_gb_per_s},
                                {"entries", entries},
                                {"final_gather", final_gather}}
                     .dump(2)
              << '\n';
    return;
  }
  std::printf("\nbench runtime: %s (%s)\n", opt.bake.c_str(), b.description.scene_name.c_str());
  std::printf("  %s", runtime_bench_table(bench).c_str());
  if (dense.empty())
    std::printf("  (no dense row: the bake has no T.npy; bake with --dump-matrices)\n");
  if (!gather)
    std::printf("  (no final gather row: the bake has none; bake with --final-gather-rays > 0)\n");
  if (!classic)
    std::printf("  (no classic row: the bake has no F.npy; bake with --dump-matrices)\n");
  std::printf(
      "  rel diff: max |y - y_C++| / max |y_C++| against the compressed C++ float32 product "
      "(bfloat16: its rounding; dense: the compression error; classic: that and K = %d against "
      "the bake's K)\n",
      k);
}

}  // namespace

void register_bench_runtime(CLI::App& bench) {
  auto opt = std::make_shared<RuntimeBenchOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "runtime",
      "Milliseconds per light update of the indirect light T b: compressed on OpenCL and in "
      "C++ (the default loop, bfloat16 where the CPU has it, and float32), against dense "
      "float32 sgemv and classic K iterations (bake with --dump-matrices for those two), and "
      "the final gather to the lit mesh's vertices (the rest of a light update), with "
      "bytes read, GB/s, the machine's read bandwidth from the same run and the default loop "
      "against the issue's targets");
  cmd->add_option("bake", opt->bake, "Bake folder with a compressed matrix")->required();
  cmd->add_option("--repeats", opt->repeats, "Timed updates per path (after one warm-up)")
      ->capture_default_str();
  cmd->add_option("--bounces", opt->bounces,
                  "K of the classic baseline (default: the bake's K, or where its auto series "
                  "converged)");
  cmd->add_flag("--json", opt->json, "Machine-readable output");
  cmd->callback([opt]() { run(*opt); });
}

}  // namespace bounce::cli
