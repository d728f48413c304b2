#include <cstdio>
#include <iostream>
#include <memory>

#include "bake/bake.h"
#include "bake/bake_writer.h"
#include "bake_report.h"
#include "commands.h"
#include "console_progress.h"
#include "scene/scene_loader.h"

namespace bounce::cli {

namespace {

void run_bench_bake(const BakeOptions& opt) {
  ConsoleProgress console(opt.quiet || opt.json);
  for (const std::string& path : expand_globs(opt.scenes)) {
    Diagnostics diagnostics;
    const Scene scene = SceneLoader(diagnostics).load(path);
    const BakeResult r = Baker(scene, opt.settings(), diagnostics).run(console.progress());
    const nlohmann::json m = make_manifest(scene, r, diagnostics);
    if (opt.json) {
      std::cout << nlohmann::json{{"scene", scene.name},
                                  {"counts", m["counts"]},
                                  {"stages", m["stages"]},
                                  {"total_seconds", m["total_seconds"]},
                                  {"settings", m["settings"]}}
                       .dump(2)
                << '\n';
      continue;
    }
    std::printf("\nbench bake: %s, %zu triangles -> %zu patches (%s), %zu samples, grid %d\n",
                scene.name.c_str(), scene.triangle_count(), r.patches.size(),
                to_string(r.settings.patch_mode).c_str(), r.samples.samples.size(),
                r.settings.voxel_resolution.value_or(0));
    print_stage_table(stdout, m);
  }
}

}  // namespace

void register_bench(CLI::App& app) {
  CLI::App* bench = app.add_subcommand(
      "bench",
      "Benchmarks: time and memory of each stage, with baselines measured in the same run");
  bench->require_subcommand(1);
  auto opt = std::make_shared<BakeOptions>();
  CLI::App* bake =
      bench->add_subcommand("bake", "Time and peak memory per bake stage (nothing is written)");
  opt->add_to(*bake, false);
  bake->callback([opt]() { run_bench_bake(*opt); });
}

}  // namespace bounce::cli
