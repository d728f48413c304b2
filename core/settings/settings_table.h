#pragma once
// Every bake setting as one row of one table: its name, type, default,
// range, help text, manifest key, command-line flag and the bake stage a
// change of it re-runs. The command line's options, the studio's panel,
// BakeSettings::validate(), the manifest's `settings` block and the re-bake
// plan all loop over these rows, so a new setting is a field of BakeSettings,
// one row here and the code that uses it (docs/architecture.md).
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "settings/bake_settings.h"
#include "settings/bake_stage.h"

namespace bounce {

enum class SettingType {
  Int,     // std::int64_t, within [min, max] or one of the named values
  Seed,    // std::uint64_t, any
  Real,    // double, within min/max
  Flag,    // bool
  Choice,  // std::string, one of the choices' names
  Text,    // std::string, any
};

// A setting's value. Monostate: unset, which the row's `unset` describes
// (the scene's own value, the codec's own ordering...). Enumerations are
// their names, the same in the CLI, the manifest and the studio's store.
using SettingValue =
    std::variant<std::monostate, bool, std::int64_t, std::uint64_t, double, std::string>;

// A name that stands for an Int value outside the row's numeric range
// (bounces: auto = 0, inf = -1); the first name of a value is how it is shown.
struct NamedValue {
  const char* name;
  std::int64_t value;
  const char* label = nullptr;  // the studio's menu entry; null: an alias it does not list
};

struct SettingChoice {
  const char* name;   // CLI, manifest and stored name
  const char* label;  // the studio's menu entry
};

struct SettingRow {
  const char* name = "";          // in errors, the studio's store and the re-bake reasons
  const char* manifest_key = "";  // in the manifest's settings.requested and settings.resolved
  const char* flag = "";          // the command line's option, e.g. "--error-budget"
  SettingType type = SettingType::Int;
  // Optional: may be unset, meaning `unset` (and, for Choice, `unset` is also
  // the name that asks for it on the command line).
  bool optional = false;
  const char* unset = "";
  const char* unset_label = "";  // the studio's menu entry for unset
  // What an unset value comes to when nothing else decides it, shown as the
  // default in the CLI's help (error_budget: 0.02).
  std::optional<double> unset_value{};
  double min = 0.0, max = 0.0;  // Int and Real
  bool min_exclusive = false, max_exclusive = false;
  const char* range_note = "";  // what an edge value means, e.g. "0: no balancing"
  std::vector<NamedValue> named{};
  std::vector<SettingChoice> choices{};
  // A Flag whose option is given to say the opposite of the default
  // (--no-pictures) is still the positive setting (pictures).
  bool flag_negates = false;
  // Only commands that write a bake folder offer it (dump_matrices, pictures).
  bool writer_only = false;
  // Another setting whose option this one's cannot be given with (CLI).
  const char* excludes = nullptr;
  // Whether the command line shows the default in its help.
  bool help_shows_default = false;
  const char* help = "";
  // The studio's label and tooltip, in artists' terms; an empty label: the
  // studio has no widget for it.
  const char* label = "";
  const char* studio_help = "";
  // The earliest stage a change of it re-runs; None: only what the writer
  // writes changes. The grid rows (voxel_resolution, patches_total) are
  // compared together, by the grid resolution they resolve to.
  BakeStage stage = BakeStage::None;
  bool grid = false;

  SettingValue (*get)(const BakeSettings&) = nullptr;
  // Monostate resets an optional setting; the value's type must match the row's.
  void (*set)(BakeSettings&, const SettingValue&) = nullptr;
};

// The rows, in the order the CLI's help and the manifest list them.
std::span<const SettingRow> settings_table();
// Throws Error for a name that is not a setting.
const SettingRow& setting_row(std::string_view name);

// The value `text` stands for (CLI text: "auto", "inf", "0.02", a choice's
// name); throws BakeSettings::InvalidSetting naming the row's setting.
SettingValue parse_setting(const SettingRow& row, const std::string& text);
// How a value reads: a choice's or named value's name, a number in %g, the
// row's `unset` text for an unset value.
std::string setting_text(const SettingRow& row, const SettingValue& value);
// Throws BakeSettings::InvalidSetting when a set value is outside the row's range.
void check_setting(const SettingRow& row, const SettingValue& value);

}  // namespace bounce
