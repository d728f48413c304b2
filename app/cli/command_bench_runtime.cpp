// `bounce bench runtime BAKE`: milliseconds per light update of every way to
// compute the indirect light T b of a compressed bake (OpenCL, C++), against
// the dense float32 matrix (when the bake holds T.npy) and the classic K
// iterations on the form factors (when it holds F.npy), with bytes read per
// update, effective bandwidth and the machine's own read bandwidth measured
// in the same run; then each light of the scene moved frame by frame, every
// step of a move timed (bench/light_move_bench.h).
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <utility>

#include "bench_commands.h"
#include "bounce/bake_folder.h"
#include "bounce/error.h"
#include "light_move_bench.h"
#include "runtime_bench.h"

namespace bounce::cli {

namespace {

struct RuntimeBenchOptions {
  std::string bake;
  int repeats = 20;
  int bounces = 0;  // classic K; 0 = the bake's
  bool json = false;
  LightMoveSettings moves;
  bool no_moves = false;
};

nlohmann::json steps_json(const LightMoveSteps& s) {
  return {{"direct_ms", s.direct}, {"indirect_ms", s.indirect}, {"product_ms", s.product},
          {"near_ms", s.near},     {"whole_ms", s.whole},       {"probes_ms", s.probes}};
}

nlohmann::json light_moves_json(const LightMoveBench& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (const LightMoveRow& r : m.rows)
    rows.push_back({{"light", r.light},
                    {"type", r.type},
                    {"every_ray", steps_json(r.every_ray)},
                    {"spread", steps_json(r.spread)},
                    {"difference_per_frame", r.difference},
                    {"frames_to_exact", r.frames_to_exact}});
  return {{"shadow_frames", m.shadow_frames},
          {"vertices", m.vertices},
          {"near_sources", m.near_sources},
          {"light_probes", m.probes},
          {"rows", rows}};
}

void print_light_moves(const LightMoveBench& m, int moves) {
  std::printf(
      "light moves (%s): %zu vertices, %zu near sources, %zu light probes, median over %d "
      "moving frames, ms\n",
      m.scene.c_str(), m.vertices, m.near_sources, m.probes, moves);
  std::printf("  %-24s %-11s %-14s %8s %8s %8s %8s %8s %8s\n", "light", "type", "shadow rays",
              "direct", "T b", "product", "near", "probes", "whole");
  for (const LightMoveRow& r : m.rows)
    for (const auto& [what, s] :
         {std::pair{std::string("every frame"), r.every_ray},
          std::pair{"over " + std::to_string(m.shadow_frames) + " frames", r.spread}}) {
      if (r.type == "area" && what != "every frame") continue;
      std::printf("  %-24s %-11s %-14s %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f\n", r.light.c_str(),
                  r.type.c_str(), what.c_str(), s.direct, s.indirect, s.product, s.near, s.probes,
                  s.whole);
    }
  for (const LightMoveRow& r : m.rows) {
    if (r.type == "area") continue;
    std::printf(
        "  %s, rays over %d frames against every ray, relative RMS per frame (moving %d, "
        "then still):",
        r.light.c_str(), m.shadow_frames, moves);
    for (double d : r.difference) std::printf(" %.4f", d);
    if (r.frames_to_exact >= 0)
      std::printf("; exact %d frames after it stopped\n", r.frames_to_exact);
    else
      std::printf("; not exact within %d frames after it stopped\n", m.shadow_frames + 1);
  }
  std::printf("  (area: the emitters do not move; frames after the first, their light kept)\n");
}

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
  std::optional<LightMoveBench> moves;
  if (gather && !opt.no_moves) moves = run_light_move_bench(opt.bake, opt.moves);
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
                                {"final_gather", final_gather},
                                {"light_moves", moves ? light_moves_json(*moves) : nullptr}}
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
  if (moves) print_light_moves(*moves, opt.moves.moves);
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
      "against the issue's targets; then each light of the scene moved frame by frame, with "
      "every step of a move timed (direct light, T b, gather product, near sources), for "
      "every shadow ray traced and for the rays spread over k frames, with the difference "
      "per frame");
  cmd->add_option("bake", opt->bake, "Bake folder with a compressed matrix")->required();
  cmd->add_option("--repeats", opt->repeats, "Timed updates per path (after one warm-up)")
      ->capture_default_str();
  cmd->add_option("--bounces", opt->bounces,
                  "K of the classic baseline (default: the bake's K, or where its auto series "
                  "converged)");
  cmd->add_option("--scene", opt->moves.scene,
                  "For the light moves: the scene the bake was made from, or one with other "
                  "lights over the same geometry (default: the manifest's)");
  cmd->add_option("--moves", opt->moves.moves,
                  "For the light moves: frames each light moves for (a point or spot light "
                  "around a circle 2% of the scene's diagonal across, a sun turned 1 degree a "
                  "frame)")
      ->capture_default_str();
  cmd->add_option("--shadow-frames", opt->moves.shadow_frames,
                  "For the light moves: k, the samples' and near sources' shadow rays and the "
                  "gather's vertex rows spread over k frames (rows 'over k frames', with their "
                  "difference from every ray per frame)")
      ->capture_default_str();
  cmd->add_flag("--no-moves", opt->no_moves,
                "Skip the light moves (each light of the scene moved frame by frame, every "
                "step timed)");
  cmd->add_flag("--json", opt->json, "Machine-readable output");
  cmd->callback([opt]() { run(*opt); });
}

}  // namespace bounce::cli
