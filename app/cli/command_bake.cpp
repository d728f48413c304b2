#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <set>
#include <string>

#include "bake/bake.h"
#include "bake/bake_writer.h"
#include "bake_report.h"
#include "base/error.h"
#include "commands.h"
#include "console_progress.h"
#include "reference_check.h"
#include "scene/scene_loader.h"

namespace bounce::cli {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct Outcome {
  std::string scene;
  bool ok = false;
  std::string detail;  // error message, or a one-line summary
  json manifest;
  std::string reference;  // --reference: one line against the path-traced reference
};

// `out` is the bake folder itself, or with `nest` the parent of one folder
// per scene (batch mode); `taken` holds the folder names a batch has used.
Outcome bake_one(const std::string& path, const fs::path& out, bool nest, const BakeOptions& opt,
                 ConsoleProgress& console, std::set<std::string>& taken) {
  Outcome o;
  o.scene = path;
  Diagnostics diagnostics;
  diagnostics.set_listener([&](const Diagnostic& d) {
    if (d.kind == Diagnostic::Kind::Warning)
      std::fprintf(stderr, "bounce: warning: %s: %s\n", d.where.c_str(), d.message.c_str());
  });
  const Scene scene = SceneLoader(diagnostics).load(path);
  o.scene = scene.name;
  std::string folder = scene.name;
  // Two scenes of a batch with one name (scans/a/mesh.ply, scans/b/mesh.ply)
  // must not share a folder: number the later ones and say so.
  for (int k = 2; nest && taken.count(folder); ++k) folder = scene.name + "-" + std::to_string(k);
  if (folder != scene.name)
    diagnostics.warn(path, "another scene of this batch is also named '" + scene.name +
                               "': baked into '" + folder + "'");
  taken.insert(folder);
  const fs::path target = nest ? out / folder : out.empty() ? fs::path("bakes") / scene.name : out;
  if (!opt.quiet)
    std::fprintf(stderr, "Baking %s (%zu triangles) into %s\n", path.c_str(),
                 scene.triangle_count(), target.string().c_str());
  const BakeResult result = Baker(scene, opt.settings(), diagnostics).run(console.progress());
  o.manifest = write_bake(target, scene, result, diagnostics);
  if (opt.reference)
    o.manifest["reference_check"] =
        check_bake_against_reference(scene, result, console.progress(), o.reference);
  o.ok = true;
  char line[256];
  std::snprintf(line, sizeof line, "%zu patches, %.2fs", result.patches.size(),
                result.total_seconds);
  o.detail = line;
  return o;
}

int run_bake(const BakeOptions& opt) {
  opt.settings().validate();  // absurd options fail before any scene is read
  const std::vector<std::string> scenes = expand_globs(opt.scenes);
  ConsoleProgress console(opt.quiet || opt.json);
  if (scenes.size() == 1) {
    // One scene: errors propagate to main(), which prints one line and exits 1.
    std::set<std::string> taken;
    Outcome o = bake_one(scenes[0], opt.out, false, opt, console, taken);
    if (opt.json)
      std::cout << o.manifest.dump(2) << '\n';
    else
      print_bake_report(stdout, o.manifest);
    if (!opt.json && !o.reference.empty()) std::printf("%s\n", o.reference.c_str());
    return 0;
  }
  // Batch: one folder per scene; a failing scene does not stop the others.
  std::vector<Outcome> outcomes;
  std::set<std::string> taken;
  const fs::path root = opt.out.empty() ? fs::path("bakes") : fs::path(opt.out);
  for (const std::string& path : scenes) {
    Outcome o;
    try {
      o = bake_one(path, root, true, opt, console, taken);
    } catch (const Cancelled&) {
      throw;
    } catch (const std::exception& e) {
      o.scene = path;
      o.ok = false;
      o.detail = e.what();
      std::fprintf(stderr, "bounce: error: %s\n", e.what());
    }
    outcomes.push_back(std::move(o));
  }
  std::size_t failed = 0;
  json summary = json::array();
  for (const Outcome& o : outcomes) {
    failed += o.ok ? 0 : 1;
    summary.push_back({{"scene", o.scene}, {"ok", o.ok}, {"detail", o.detail}});
  }
  if (opt.json) {
    std::cout << json{{"scenes", summary}, {"failed", failed}}.dump(2) << '\n';
  } else {
    std::printf("\n%-28s %-6s %s\n", "scene", "status", "detail");
    for (const Outcome& o : outcomes)
      std::printf("%-28s %-6s %s\n", o.scene.c_str(), o.ok ? "ok" : "FAILED", o.detail.c_str());
    std::printf("\n%zu of %zu scenes baked into %s\n", outcomes.size() - failed, outcomes.size(),
                root.string().c_str());
  }
  return failed == 0 ? 0 : failed == outcomes.size() ? 1 : 2;
}

}  // namespace

void register_bake(CLI::App& app) {
  auto opt = std::make_shared<BakeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "bake",
      "Bake scenes: voxel grid, virtual patches, form factors, the multi-bounce transport matrix "
      "and its compression, written to a bake folder "
      "(manifest.json + .npy arrays, see docs/bake-format.md). Exit codes: 0 ok, 1 error "
      "(or every scene of a batch failed), 2 some scenes of a batch failed, 130 cancelled.");
  opt->add_to(*cmd, true);
  cmd->callback([opt]() {
    const int code = run_bake(*opt);
    if (code != 0) throw ExitCode{code};
  });
}

}  // namespace bounce::cli
