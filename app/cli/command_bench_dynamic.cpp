// `bounce bench dynamic BAKE`: the dynamic variants of paper 003 (local
// matrix, temporal radiosity, frame graph with transient-memory aliasing)
// against the full multi-bounce product and classic radiosity, as one table
// like the paper's Table 2, then the local-matrix update against LU
// recomputation and the transient memory with and without aliasing (the
// paper's Table 1). Needs the exact matrices: bake with --dump-matrices.
#include <cstdio>
#include <iostream>
#include <memory>

#include "bake/bake_reader.h"
#include "base/error.h"
#include "bench_commands.h"
#include "dynamic/dynamic_bench.h"
#include "io/npy.h"

namespace bounce::cli {

namespace {

struct DynamicBenchOptions {
  std::string bake;
  int samples = 64;
  float weight = 0.9f;
  int repeats = 10;
  int light = 0, jump_to = 1;
  int bounces = 16;
  bool no_local = false;
  bool json = false;
};

void run(const DynamicBenchOptions& opt) {
  if (opt.samples < 1 || opt.samples > 1 << 20)
    throw Error("--samples", "must be between 1 and 1048576");
  if (!(opt.weight >= 0.0f && opt.weight < 1.0f)) throw Error("--weight", "must be in [0, 1)");
  if (opt.repeats < 1 || opt.repeats > 10000)
    throw Error("--repeats", "must be between 1 and 10000");
  if (opt.bounces < 1 || opt.bounces > 1000) throw Error("--bounces", "must be between 1 and 1000");
  const LoadedBake b = BakeReader::read(opt.bake, true);
  if (b.dense.empty())
    throw Error(opt.bake, "holds no exact transport matrix T.npy: bake with --dump-matrices");
  const auto lights = static_cast<int>(b.probe.first_hit.size());
  for (const auto& [name, index] : {std::pair{"--light", opt.light}, {"--jump-to", opt.jump_to}})
    if (index < 0 || index >= lights)
      throw Error(name, "light " + std::to_string(index) + " does not exist (the bake has " +
                            std::to_string(lights) + " evaluation lights)");
  if (opt.light == opt.jump_to) throw Error("--jump-to", "must differ from --light");

  DynamicBenchInput in;
  in.n = b.size();
  for (const auto& t : b.dense) in.transport.push_back(t.data());
  in.channel_of_rgb = b.channel_of_rgb;
  for (const Patch& p : b.patches.patches) in.albedo.push_back(p.albedo);
  in.area = b.probe.area;
  in.light = b.probe.first_hit[static_cast<std::size_t>(opt.light)];
  in.jumped_light = b.probe.first_hit[static_cast<std::size_t>(opt.jump_to)];
  in.classic_bounces = opt.bounces;
  NpyArray<float> f;
  const auto f_path = std::filesystem::path(opt.bake) / "F.npy";
  if (std::filesystem::exists(f_path)) {
    f = read_npy_f32(f_path);
    if (f.data.size() != in.n * in.n) throw Error(f_path.string(), "is not N x N");
    in.form_factors = f.data.data();
  }
  DynamicBenchSettings settings;
  settings.temporal.samples_per_patch = opt.samples;
  settings.temporal.history_weight = opt.weight;
  settings.repeats = opt.repeats;
  settings.local_matrix = !opt.no_local;
  const DynamicBench bench = run_dynamic_bench(in, settings);

  if (opt.json) {
    nlohmann::json methods = nlohmann::json::array();
    for (const DynamicMethodRow& r : bench.methods)
      methods.push_back({{"method", r.method},
                         {"available", r.available},
                         {"note", r.note},
                         {"ms_per_frame", r.ms_per_frame},
                         {"error_after_1_4_16_64", r.error},
                         {"ghosting_frames", r.ghosting_frames},
                         {"persistent_bytes", r.persistent_bytes},
                         {"transient_bytes", r.transient_bytes}});
    nlohmann::json local = nlohmann::json::array();
    for (const LocalMatrixRow& r : bench.local)
      local.push_back({{"patch", r.patch},
                       {"sigma", r.sigma},
                       {"remove_ms", r.remove_ms},
                       {"add_ms", r.add_ms},
                       {"recompute_ms", r.recompute_ms},
                       {"remove_vs_recompute", r.remove_vs_recompute},
                       {"round_trip", r.round_trip}});
    nlohmann::json memory = nlohmann::json::array();
    for (const TransientMemoryRow& r : bench.memory)
      memory.push_back({{"scene", r.scene},
                        {"patches", r.patches},
                        {"unaliased_bytes", r.unaliased_bytes},
                        {"aliased_bytes", r.aliased_bytes}});
    std::cout << nlohmann::json{{"bake", opt.bake},          {"patches", bench.n},
                                {"samples", opt.samples},    {"weight", opt.weight},
                                {"methods", methods},        {"local_matrix", local},
                                {"transient_memory", memory}}
                     .dump(2)
              << '\n';
    return;
  }
  std::printf(
      "\nbench dynamic: %s (%s), %zu patches, %d samples per patch, w = %.3g, light %d "
      "-> %d\n",
      opt.bake.c_str(), b.manifest.at("scene").at("name").get<std::string>().c_str(), bench.n,
      opt.samples, static_cast<double>(opt.weight), opt.light, opt.jump_to);
  std::printf("%s", dynamic_bench_table(bench).c_str());
  std::printf(
      "err@f: area-weighted relative RMS of the indirect light against the full product after f "
      "frames of one light; ghost: frames after the light jumps until the error is back under "
      "1.5x its err@64 (at least 1e-3); persist: matrices/tables and the history; transient: "
      "the frame graph's per-frame buffers incl. a local-matrix update, without aliasing except "
      "in the aliasing row.\n");
}

}  // namespace

void register_bench_dynamic(CLI::App& bench) {
  auto opt = std::make_shared<DynamicBenchOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "dynamic",
      "Dynamic radiosity (paper 003): full multi-bounce product vs temporal radiosity (alias "
      "tables, C++ and OpenCL, with and without frame-graph memory aliasing) vs classic; ms per "
      "frame, error after 1/4/16/64 frames, ghosting after a light jump, memory; local-matrix "
      "rank-1 updates vs LU. Needs a bake made with --dump-matrices");
  cmd->add_option("bake", opt->bake, "Bake folder with T.npy (and F.npy)")->required();
  cmd->add_option("--samples", opt->samples, "Temporal radiosity: samples per patch and frame")
      ->capture_default_str();
  cmd->add_option("--weight", opt->weight, "Temporal radiosity: history weight w")
      ->capture_default_str();
  cmd->add_option("--repeats", opt->repeats, "Timed frames per method (after one warm-up)")
      ->capture_default_str();
  cmd->add_option("--light", opt->light, "Evaluation light before the jump")->capture_default_str();
  cmd->add_option("--jump-to", opt->jump_to, "Evaluation light after the jump")
      ->capture_default_str();
  cmd->add_option("--bounces", opt->bounces, "K of the classic baseline")->capture_default_str();
  cmd->add_flag("--no-local", opt->no_local,
                "Skip the local-matrix rows (they factorise T twice by LU)");
  cmd->add_flag("--json", opt->json, "Machine-readable output");
  cmd->callback([opt]() { run(*opt); });
}

}  // namespace bounce::cli
