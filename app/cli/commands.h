#pragma once
// The `bounce` subcommands. Each registers its options on a CLI11 subcommand
// and runs through the same core functions the studio uses.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "bake/bake_settings.h"

namespace bounce::cli {

// Thrown by a subcommand to end with a non-zero exit code after it has
// printed its own report.
struct ExitCode {
  int code;
};

// Bake options shared by `bake` and `bench bake`.
struct BakeOptions {
  std::vector<std::string> scenes;
  std::string out;
  int voxel = 0;
  int patches_total = 0;
  int patches_per_voxel = 3;
  std::string patch_mode = "virtual";
  int samples_per_face = 4;
  int visibility_rays = 8;
  int closure_rays = BakeSettings{}.closure_rays;
  int final_gather_rays = BakeSettings{}.final_gather_rays;
  std::uint64_t seed = 1;
  bool dump_matrices = false;
  std::string bounces = "auto";
  std::string codec = "auto";
  std::string ordering = "auto";
  double kept_fraction = 0.04;
  double error_budget = BakeSettings::kDefaultErrorBudget;
  double size_limit = BakeSettings::kDefaultSizeLimit;
  std::string gemm = "auto";
  std::string out_of_core = "auto";
  std::string out_of_core_dir;
  bool no_pictures = false;
  bool reference = false;  // bake: also measure against the path-traced reference
  bool json = false;
  bool quiet = false;
  CLI::Option* voxel_option = nullptr;
  CLI::Option* patches_total_option = nullptr;
  CLI::Option* patches_per_voxel_option = nullptr;
  CLI::Option* samples_per_face_option = nullptr;
  CLI::Option* kept_fraction_option = nullptr;
  CLI::Option* error_budget_option = nullptr;
  CLI::Option* size_limit_option = nullptr;

  void add_to(CLI::App& cmd, bool with_output);
  BakeSettings settings() const;
};

void register_bake(CLI::App& app);
void register_info(CLI::App& app);
void register_bench(CLI::App& app);
void register_solve(CLI::App& app);
void register_report(CLI::App& app);

// Expands arguments holding * or ? (quoted globs) into sorted matching paths.
std::vector<std::string> expand_globs(const std::vector<std::string>& args);

}  // namespace bounce::cli
