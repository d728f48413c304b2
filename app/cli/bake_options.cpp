#include <glob.h>

#include <algorithm>

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
  voxel_option = cmd.add_option(
      "--voxel", voxel,
      "Voxel grid resolution: cells along the scene's longest axis. More cells = more, smaller "
      "patches (default: the scene's own, else 16)");
  patches_total_option =
      cmd.add_option("--patches-total", patches_total,
                     "Aim for about this many patches; picks the voxel resolution for you")
          ->excludes(voxel_option);
  patches_per_voxel_option = cmd.add_option(
      "--patches-per-voxel", patches_per_voxel,
      "Virtual patches kept per voxel after clustering (default: the scene's, else 3: a box "
      "corner holds three orientations)");
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
  cmd.add_option("--seed", seed, "Seed of every random stream (results are reproducible)")
      ->capture_default_str();
  if (with_output)
    cmd.add_flag("--dump-matrices", dump_matrices,
                 "Also write the N x N form-factor matrix as F.npy");
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
  s.seed = seed;
  s.dump_matrices = dump_matrices;
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
