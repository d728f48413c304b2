#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "bake_report.h"
#include "bounce/bake.h"
#include "bounce/bake_folder.h"
#include "bounce/error.h"
#include "bounce/scene.h"
#include "commands.h"
#include "console_progress.h"
#include "flag_spelling.h"
#include "lit_bake_mesh.h"
#include "reference_check.h"
#ifdef BOUNCE_HAVE_MPI
#include "bounce/distributed_bake.h"
#endif

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
  std::string glb;        // --export-glb: the file written
};

// FOLDER.glb beside the bake folder FOLDER ("bakes/box/" -> "bakes/box.glb";
// "." -> "../NAME.glb" as an absolute path).
fs::path glb_beside(const fs::path& folder) {
  fs::path p = folder.lexically_normal();
  if (p.filename() == "." || p.filename() == "..") p = fs::absolute(p).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  return p.parent_path() / (p.filename().string() + ".glb");
}

// A distributed bake (mpirun): this process's share, and the agreement on
// errors every rank must see. Null members: a single-process bake.
struct Distributed {
  BakeDistribution* distribution = nullptr;
  // Loads the scene on every rank; throws on every rank if any failed.
  std::function<Scene(const std::string&, Diagnostics&)> load_everywhere;
  bool root() const { return !distribution || distribution->is_root(); }
};

// Whether `target` already holds this bake (same content key, complete and
// readable): then it is kept as it is. A folder that holds something else
// than a usable bake is baked again, and the warning says why.
bool up_to_date(const std::optional<std::string>& content, const Scene& scene,
                const BakeSettings& settings, const fs::path& target, Diagnostics& diagnostics) {
  if (!content) return false;
  const std::string key = bake_key(*content, scene, settings);
  std::string why;
  const std::optional<std::string> stored = stored_bake_key(target, &why);
  if (!why.empty()) diagnostics.warn(target.string(), "not reused, baking again: " + why);
  return stored == key;
}

// The outcome of a reused bake folder: its manifest, as a bake would print it.
Outcome reused_outcome(Outcome o, const fs::path& target, const BakeOptions& opt) {
  o.manifest = read_manifest_json(target / bake_file::kManifest);
  o.manifest["reused"] = true;
  if (!opt.quiet)
    std::fprintf(stderr, "%s is up to date (key %s): reused, not baked; --force bakes again\n",
                 target.string().c_str(), o.manifest.value("key", std::string()).c_str());
  o.ok = true;
  const json counts = o.manifest.value("counts", json::object());
  o.detail = "up to date, " + std::to_string(counts.value("patches", 0)) + " patches, reused";
  return o;
}

// `out` is the bake folder itself, or with `nest` the parent of one folder
// per scene (batch mode); `taken` holds the folder names a batch has used.
Outcome bake_one(const std::string& path, const fs::path& out, bool nest, const BakeOptions& opt,
                 ConsoleProgress& console, std::set<std::string>& taken,
                 const Distributed& distributed = {}) {
  Outcome o;
  o.scene = path;
  Diagnostics diagnostics;
  const bool root = distributed.root();  // only the root speaks and writes
  diagnostics.set_listener([&](const Diagnostic& d) {
    if (root && d.kind == Diagnostic::Kind::Warning)
      std::fprintf(stderr, "bounce: warning: %s: %s\n", d.where.c_str(),
                   with_flag_spellings(d.message).c_str());
  });
  const Scene scene = distributed.load_everywhere ? distributed.load_everywhere(path, diagnostics)
                                                  : SceneLoader(diagnostics).load(path);
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
  // The files hashed once, as loaded: the check and the bake's key agree.
  const std::optional<std::string> content = scene_content_hash(scene);
  // A distributed bake's ranks would each have to agree on the folder, and
  // --reference checks the bake in memory: both always bake.
  if (!opt.force && !opt.reference && !distributed.distribution &&
      up_to_date(content, scene, opt.settings(), target, diagnostics)) {
    Outcome reused = reused_outcome(std::move(o), target, opt);
    if (opt.export_glb) {
      const fs::path glb = glb_beside(target);
      export_bake_glb(target, scene, glb, console.progress());
      reused.glb = glb.string();
    }
    return reused;
  }
  if (!opt.quiet && root)
    std::fprintf(stderr, "Baking %s (%zu triangles) into %s\n", path.c_str(),
                 scene.triangle_count(), target.string().c_str());
  Baker baker(scene, opt.settings(), diagnostics);
  baker.set_distribution(distributed.distribution);
  baker.set_scene_content(content);
  const BakeResult result = baker.run(console.progress());
  if (!root) {
    o.ok = true;  // this rank's share is done; the root writes the bake
    return o;
  }
  o.manifest = write_bake(target, scene, result, diagnostics);
  if (opt.reference)
    o.manifest["reference_check"] =
        check_bake_against_reference(scene, result, console.progress(), o.reference);
  if (opt.export_glb) {
    const fs::path glb = glb_beside(target);
    export_bake_glb(target, scene, glb, console.progress());
    o.glb = glb.string();
  }
  o.ok = true;
  char line[256];
  std::snprintf(line, sizeof line, "%zu patches, %.2fs", result.patches.size(),
                result.total_seconds);
  o.detail = line;
  if (!o.glb.empty()) o.detail += ", lit mesh " + o.glb;
  return o;
}

void print_single(const BakeOptions& opt, const Outcome& o) {
  if (opt.json)
    std::cout << o.manifest.dump(2) << '\n';
  else
    print_bake_report(stdout, o.manifest);
  if (!opt.json && !o.reference.empty()) std::printf("%s\n", o.reference.c_str());
  if (!opt.json && !o.glb.empty()) std::printf("lit mesh (binary glTF): %s\n", o.glb.c_str());
}

#ifdef BOUNCE_HAVE_MPI
// `mpirun -np R bounce bake SCENE`: one scene shared by R ranks
// (core/distributed, docs/cluster.md). Errors every rank meets (a bad scene,
// ranks that disagree) are agreed on and reported once by rank 0; an error
// only one rank meets ends the whole job, since the others may be waiting for
// it. The bake folder is written by rank 0, after the bake, atomically.
int run_distributed_bake(const BakeOptions& opt, const std::vector<std::string>& scenes,
                         const MpiSession& mpi) {
  if (scenes.size() != 1 && !mpi.is_root()) throw ExitCode{1};  // rank 0 says why
  if (scenes.size() != 1)
    throw Error("bake", "a distributed bake (mpirun) takes one scene, got " +
                            std::to_string(scenes.size()) + "; bake them one by one");
  MpiBakeDistribution distribution(mpi);
  Distributed distributed;
  distributed.distribution = &distribution;
  distributed.load_everywhere = [&](const std::string& path, Diagnostics& diagnostics) {
    std::optional<Scene> scene;
    std::string error;
    try {
      scene = SceneLoader(diagnostics).load(path);
    } catch (const Error& e) {
      error = e.what();
    }
    mpi.agree(scene.has_value(), error);
    return std::move(*scene);
  };
  ConsoleProgress console(opt.quiet || opt.json || !mpi.is_root());
  try {
    std::set<std::string> taken;
    const Outcome o = bake_one(scenes[0], opt.out, false, opt, console, taken, distributed);
    if (mpi.is_root()) print_single(opt, o);
    return 0;
  } catch (const RankFailure& e) {
    if (e.reported_here()) throw;  // rank 0 prints the one line
    throw ExitCode{1};
  } catch (const std::exception& e) {
    const bool cancelled = dynamic_cast<const Cancelled*>(&e) != nullptr;
    if (mpi.is_root())
      std::fprintf(stderr, "bounce: %s%s\n", cancelled ? "" : "error: ", e.what());
    else
      std::fprintf(stderr, "bounce: error: rank %d of %d: %s\n", mpi.rank(), mpi.size(), e.what());
    mpi.abort(cancelled ? 130 : 1);
  }
}
#endif

int run_bake(const BakeOptions& opt) {
#ifdef BOUNCE_HAVE_MPI
  // Started by mpirun/srun: join the job; one rank is the plain bake.
  std::optional<MpiSession> mpi;
  if (MpiSession::launched_by_mpi()) mpi.emplace();
  if (mpi && mpi->size() > 1) {
    std::vector<std::string> scenes;
    try {
      opt.settings().validate();
      scenes = expand_globs(opt.scenes);
    } catch (const Error&) {
      if (!mpi->is_root()) throw ExitCode{1};  // every rank fails alike: rank 0 says it
      throw;
    }
    return run_distributed_bake(opt, scenes, *mpi);
  }
#endif
  opt.settings().validate();  // absurd options fail before any scene is read
  const std::vector<std::string> scenes = expand_globs(opt.scenes);
  ConsoleProgress console(opt.quiet || opt.json);
  if (scenes.size() == 1) {
    // One scene: errors propagate to main(), which prints one line and exits 1.
    std::set<std::string> taken;
    const Outcome o = bake_one(scenes[0], opt.out, false, opt, console, taken);
    print_single(opt, o);
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
    json entry = {{"scene", o.scene}, {"ok", o.ok}, {"detail", o.detail}};
    if (!o.glb.empty()) entry["glb"] = o.glb;
    summary.push_back(std::move(entry));
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
      "(or every scene of a batch failed), 2 some scenes of a batch failed, 130 cancelled. "
      "With --export-glb, a scene whose export fails counts as failed.");
  opt->add_to(*cmd, true);
  cmd->callback([opt]() {
    const int code = run_bake(*opt);
    if (code != 0) throw ExitCode{code};
  });
}

}  // namespace bounce::cli
