#include <glob.h>

#include <algorithm>
#include <string>
#include <variant>

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
  if (with_output)
    cmd.add_flag("--export-glb", export_glb,
                 "Also light each bake with its scene's lights and write the lit mesh as binary "
                 "glTF beside the bake folder (bakes/box -> bakes/box.glb): vertex colours, the "
                 "scene's materials with their textures embedded, texture coordinates; Blender "
                 "and glTF viewers open it (docs/export.md)");
  if (with_output)
    cmd.add_flag("--force", force,
                 "Bake even when the output folder already holds a complete bake of the same "
                 "scene contents and settings (same content key in its manifest.json, "
                 "docs/bake-format.md); without it such a folder is reused as it is");
  for (const SettingRow& row : settings_table()) {
    if (row.writer_only && !with_output) continue;
    CLI::Option* o = nullptr;
    if (row.type == SettingType::Flag) {
      o = cmd.add_flag(row.flag, flags[row.name], row.help);
    } else {
      std::string& text = texts[row.name];
      o = cmd.add_option(row.flag, text, row.help);
      if (row.help_shows_default) {
        const SettingValue d = row.get(BakeSettings{});
        text = std::holds_alternative<std::monostate>(d) && row.unset_value
                   ? setting_text(row, *row.unset_value)
                   : setting_text(row, d);
        o->capture_default_str();
      }
      // The number types CLI11 checks before parse_setting reads the text,
      // named in the help as they always were.
      if (row.type == SettingType::Choice) {
        std::vector<std::string> names;
        if (row.optional) names.emplace_back(row.unset);
        for (const SettingChoice& c : row.choices) names.emplace_back(c.name);
        o->check(CLI::IsMember(names));
      } else if (row.type == SettingType::Int && row.named.empty()) {
        o->check(CLI::TypeValidator<int>(""))->type_name("INT");
      } else if (row.type == SettingType::Seed) {
        o->check(CLI::TypeValidator<std::uint64_t>(""))->type_name("UINT");
      } else if (row.type == SettingType::Real) {
        o->check(CLI::TypeValidator<double>(""))->type_name("FLOAT");
      }
    }
    if (row.excludes)
      if (CLI::Option* other = option(row.excludes)) o->excludes(other);
    options[row.name] = o;
  }
  cmd.add_flag("--json", json, "Print a machine-readable summary on stdout");
  cmd.add_flag("--quiet,-q", quiet, "No progress bars (warnings and errors still print)");
}

CLI::Option* BakeOptions::option(std::string_view setting) const {
  const auto it = options.find(setting);
  return it == options.end() ? nullptr : it->second;
}

bool BakeOptions::given(std::string_view setting) const {
  const CLI::Option* o = option(setting);
  return o && o->count() > 0;
}

BakeSettings BakeOptions::settings() const {
  BakeSettings s;
  for (const SettingRow& row : settings_table()) {
    if (!given(row.name)) continue;
    if (row.type == SettingType::Flag)
      row.set(s, flags.at(row.name) != row.flag_negates);
    else
      row.set(s, parse_setting(row, texts.at(row.name)));
  }
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
