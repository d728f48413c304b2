#pragma once
// The `bounce` subcommands. Each registers its options on a CLI11 subcommand
// and runs through the same core functions the studio uses.
#include <CLI/CLI.hpp>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "bounce/settings.h"

namespace bounce::cli {

// Thrown by a subcommand to end with a non-zero exit code after it has
// printed its own report.
struct ExitCode {
  int code;
};

// Bake options shared by `bake` and `bench bake`: one per row of the
// settings table (bounce/settings.h), with the row's flag and help.
struct BakeOptions {
  std::vector<std::string> scenes;
  std::string out;
  bool reference = false;  // bake: also measure against the path-traced reference
  // bake: also light each bake with its scene's lights and write the lit
  // mesh, materials and textures as binary glTF beside the bake folder
  // (FOLDER.glb). Not a bake setting: it changes nothing in the folder.
  bool export_glb = false;
  bool json = false;
  bool quiet = false;
  // bake: bake even when the output folder holds an up-to-date bake (one
  // whose content key equals this bake's, core/bake/bake_key.h).
  bool force = false;
  // Each setting's text as given on the command line, and its option.
  std::map<std::string, std::string, std::less<>> texts;
  std::map<std::string, bool, std::less<>> flags;
  std::map<std::string, CLI::Option*, std::less<>> options;

  void add_to(CLI::App& cmd, bool with_output);
  // The option of a setting (settings_table.h); null when this command does
  // not offer it.
  CLI::Option* option(std::string_view setting) const;
  bool given(std::string_view setting) const;
  // Options not given leave the defaults (and the scene's) in force; a value
  // that cannot be read throws BakeSettings::InvalidSetting.
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
