#include <glob.h>

#include <algorithm>
#include <string>

#include "commands.h"

namespace bounce::cli {

void BakeOptions::add_to(CLI::App& cmd, bool with_output) {
  cmd.add_option("scenes", scenes,
                 "Scene(s): a scene folder, a scene.json, or a mesh file (OBJ+MTL, PLY, glTF). "
                 "Several scenes (or a quoted glob) bake one after another.")
      ->required();
  if (with_output)
    cmd.add_option("--out,-o", out,
                   "Output folder. One scene: the bake folder itself. Several scenes: one "
                   "sub-folder per scene. Default: bakes/<scene-name>");
  if (with_output)
    cmd.add_flag("--reference", reference,
                 "Also print the bake's error against the path-traced reference "
                 "(docs/reference.md) and its run time; the first run per scene renders the "
                 "reference (seconds), later runs read it from the cache");
  voxel_option = cmd.add_option(
      "--voxel", voxel,
      "Voxel grid resolution: cells along the scene's longest axis. More cells = more, smaller "
      "patches (default: the scene's own, else 16)");
  patches_total_option =
      cmd.add_option("--patches-total", patches_total,
                     "This many patches: picks the voxel resolution for you, then (virtual "
                     "patches) spends the budget where merging costs most, so curved or unevenly "
                     "lit voxels keep more patches than flat walls")
          ->excludes(voxel_option);
  patches_per_voxel_option = cmd.add_option(
      "--patches-per-voxel", patches_per_voxel,
      "Virtual patches kept per voxel after clustering (default: the scene's, else 3: a box "
      "corner holds three orientations); with --patches-total, the average used to pick the grid");
  cmd.add_option("--patches", patch_mode,
                 "virtual: cluster samples into virtual patches (paper 001, default); voxel: one "
                 "patch per voxel and normal direction (the baseline)")
      ->check(CLI::IsMember({"virtual", "voxel"}))
      ->capture_default_str();
  samples_per_face_option = cmd.add_option(
      "--samples-per-face", samples_per_face,
      "Rays per voxel face are N x N (default: the scene's, else 4: 96 rays per voxel)");
  cmd.add_option("--visibility-rays", visibility_rays,
                 "Shadow rays per patch pair for form-factor visibility")
      ->capture_default_str();
  cmd.add_option("--closure-rays", closure_rays,
                 "Rays per patch measuring the share of its light that lands on sampled surface "
                 "(its closure, 1 in a closed room); the form factors are then balanced so each "
                 "row sums to it and reciprocity is exact. 0: keep the raw quadrature")
      ->capture_default_str();
  cmd.add_option("--final-gather-rays", final_gather_rays,
                 "Rays per vertex of the lit mesh: each vertex gathers its indirect light from "
                 "the patches it sees through these ray-traced form factors, stored in the bake "
                 "(gather_*.npy). 0: no final gather; vertices take the nearest patches' light")
      ->capture_default_str();
  cmd.add_option("--seed", seed, "Seed of every random stream (results are reproducible)")
      ->capture_default_str();
  cmd.add_option("--bounces", bounces,
                 "Light bounces folded into the transport matrix: auto (stop when the next bounce "
                 "adds less than 0.1% of the light), inf (the exact limit, by LU), or 1..64")
      ->capture_default_str();
  cmd.add_option("--gemm", gemm,
                 "Matrix products on: auto (time both, keep the faster), openblas (CPU) or "
                 "clblast (OpenCL)")
      ->check(CLI::IsMember({"auto", "openblas", "clblast"}))
      ->capture_default_str();
  cmd.add_option("--out-of-core", out_of_core,
                 "Keep the finished N x N matrices (form factors, transport) in memory-mapped "
                 "temporary files the kernel can page out: auto (when the dense matrices would "
                 "take more than half the machine's memory), on, off. Same result either way")
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->capture_default_str();
  cmd.add_option("--out-of-core-dir", out_of_core_dir,
                 "Folder of the temporary matrix files (default: $TMPDIR, else /tmp); they are "
                 "deleted as soon as they are created and vanish with the process");
  cmd.add_option("--codec", codec,
                 "How the transport matrix is stored: auto (ours, or dense when it is under "
                 "1 MiB and compression would not pay), dense (exact float32), paper (the "
                 "published pipeline: 4% kept, greedy L1 reordering, libsquish BC1), ours "
                 "(entries kept and blocks weighted by the light they carry, better "
                 "reordering, kept fraction from the error budget)")
      ->check(CLI::IsMember({"auto", "dense", "paper", "ours"}))
      ->capture_default_str();
  cmd.add_option("--ordering", ordering,
                 "Row/column ordering before block encoding (paper and ours): auto (the codec's "
                 "own: paper-2-passes for paper, ours for ours), none, paper-1-pass, "
                 "paper-2-passes (the published greedy L1 tour) or ours (sketch + tour + 4-row "
                 "refinement)")
      ->check(CLI::IsMember({"auto", "none", "paper-1-pass", "paper-2-passes", "ours"}))
      ->capture_default_str();
  kept_fraction_option = cmd.add_option(
      "--kept-fraction", kept_fraction,
      "Share of each channel's largest entries kept exactly (default: the paper's 0.04 for "
      "--codec paper; chosen from --error-budget for ours)");
  error_budget_option =
      cmd.add_option("--error-budget", error_budget,
                     "Relative RMS error of the indirect light the compressed matrix may cause "
                     "(area-weighted over patches, on the worst of the evaluation lights: the "
                     "scene's lights, four point lights, five suns); ours keeps the fewest "
                     "entries that meet it (default: the scene's bake block, else 0.02)")
          ->capture_default_str()
          ->excludes(kept_fraction_option);
  size_limit_option =
      cmd.add_option("--size-limit", size_limit,
                     "Largest size the error budget's search may give the compressed matrix, as "
                     "a share of dense float32 RGB (0.125: at least 8x smaller); when no kept "
                     "fraction within it meets the budget, the bake keeps the largest that fits "
                     "and says so")
          ->capture_default_str()
          ->excludes(kept_fraction_option);
  if (with_output) {
    cmd.add_flag("--dump-matrices", dump_matrices,
                 "Also write the N x N form-factor matrix as F.npy and the exact transport "
                 "matrix as T.npy");
    cmd.add_flag("--no-pictures", no_pictures, "Do not write the matrix and error pictures (PNG)");
  }
  cmd.add_flag("--json", json, "Print a machine-readable summary on stdout");
  cmd.add_flag("--quiet,-q", quiet, "No progress bars (warnings and errors still print)");
}

BakeSettings BakeOptions::settings() const {
  BakeSettings s;
  // Options not given leave the scene's defaults in force. Given values,
  // absurd ones included, go to validate(), which names the option.
  if (voxel_option->count() > 0) s.voxel_resolution = voxel;
  if (patches_total_option->count() > 0) s.patches_total = patches_total;
  if (patches_per_voxel_option->count() > 0) s.patches_per_voxel = patches_per_voxel;
  s.patch_mode = patch_mode == "voxel" ? PatchMode::Voxel : PatchMode::Virtual;
  if (samples_per_face_option->count() > 0) s.samples_per_face = samples_per_face;
  s.visibility_rays = visibility_rays;
  s.closure_rays = closure_rays;
  s.final_gather_rays = final_gather_rays;
  s.seed = seed;
  s.dump_matrices = dump_matrices;
  s.pictures = !no_pictures;
  if (bounces == "auto") {
    s.transport.bounces = TransportSettings::kAutoBounces;
  } else if (bounces == "inf" || bounces == "infinity") {
    s.transport.bounces = TransportSettings::kInfiniteBounces;
  } else {
    // Anything else must be a whole number; validate() checks its range.
    std::size_t used = 0;
    int k = 0;
    try {
      k = std::stoi(bounces, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != bounces.size() || k < 1)
      throw BakeSettings::InvalidSetting(
          "--bounces", "must be auto, inf or a number of bounces 1.." +
                           std::to_string(TransportSettings::kMaxBounces) + ", got '" + bounces +
                           "'");
    s.transport.bounces = k;
  }
  s.transport.backend = gemm == "openblas"  ? TransportSettings::Backend::OpenBLAS
                        : gemm == "clblast" ? TransportSettings::Backend::CLBlast
                                            : TransportSettings::Backend::Auto;
  s.out_of_core = out_of_core == "on"    ? OutOfCore::On
                  : out_of_core == "off" ? OutOfCore::Off
                                         : OutOfCore::Auto;
  s.out_of_core_dir = out_of_core_dir;
  s.codec = codec == "dense"   ? CodecChoice::Dense
            : codec == "paper" ? CodecChoice::Paper
            : codec == "ours"  ? CodecChoice::Ours
                               : CodecChoice::Auto;
  for (OrderingMethod m :
       {OrderingMethod::None, OrderingMethod::Paper1, OrderingMethod::Paper2, OrderingMethod::Ours})
    if (ordering == ordering_name(m)) s.ordering = m;
  if (kept_fraction_option->count() > 0) s.kept_fraction = kept_fraction;
  if (error_budget_option->count() > 0) s.error_budget = error_budget;
  if (size_limit_option->count() > 0) s.size_limit = size_limit;
  return s;
}

std::vector<std::string> expand_globs(const std::vector<std::string>& args) {
  std::vector<std::string> out;
  for (const std::string& a : args) {
    if (a.find_first_of("*?[") == std::string::npos) {
      out.push_back(a);
      continue;
    }
    glob_t g{};
    if (::glob(a.c_str(), 0, nullptr, &g) == 0) {
      std::vector<std::string> matches(g.gl_pathv, g.gl_pathv + g.gl_pathc);
      std::sort(matches.begin(), matches.end());
      out.insert(out.end(), matches.begin(), matches.end());
    } else {
      out.push_back(a);  // no match: let the loader report the missing file
    }
    ::globfree(&g);
  }
  return out;
}

}  // namespace bounce::cli
