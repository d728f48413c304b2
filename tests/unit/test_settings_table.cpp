// The settings table (core/settings/settings_table.h): the settings it lists,
// their defaults against validate(), range errors that name the setting,
// text round trips, and the re-bake stage each row says a change re-runs.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "bake/rebake_plan.h"
#include "scene/scene_loader.h"
#include "settings/bake_settings.h"
#include "settings/settings_table.h"

namespace bounce {
namespace {

// Every setting, its command-line option (scripts depend on these names) and
// the stage a change of it re-runs, written out independently of the table.
struct Expected {
  const char* flag;
  BakeStage stage;
};
const std::map<std::string, Expected>& expected() {
  static const std::map<std::string, Expected> e = {
      {"voxel_resolution", {"--voxel", BakeStage::Geometry}},
      {"patches_total", {"--patches-total", BakeStage::Geometry}},
      {"patches_per_voxel", {"--patches-per-voxel", BakeStage::Patches}},
      {"patch_mode", {"--patches", BakeStage::Patches}},
      {"samples_per_face", {"--samples-per-face", BakeStage::Geometry}},
      {"visibility_rays", {"--visibility-rays", BakeStage::Patches}},
      {"closure_rays", {"--closure-rays", BakeStage::Patches}},
      {"final_gather_rays", {"--final-gather-rays", BakeStage::Patches}},
      {"final_gather_near", {"--final-gather-near", BakeStage::Patches}},
      {"final_gather_near_min_rays", {"--final-gather-near-min-rays", BakeStage::Patches}},
      {"final_gather_spots", {"--final-gather-spots", BakeStage::Patches}},
      {"light_probes", {"--light-probes", BakeStage::Patches}},
      {"light_probe_volumes", {"--light-probe-volumes", BakeStage::Patches}},
      {"light_probes_max", {"--light-probes-max", BakeStage::Patches}},
      {"seed", {"--seed", BakeStage::Geometry}},
      {"bounces", {"--bounces", BakeStage::Transport}},
      {"gemm", {"--gemm", BakeStage::Transport}},
      {"out_of_core", {"--out-of-core", BakeStage::None}},
      {"out_of_core_dir", {"--out-of-core-dir", BakeStage::None}},
      {"codec", {"--codec", BakeStage::Compress}},
      {"ordering", {"--ordering", BakeStage::Compress}},
      {"kept_fraction", {"--kept-fraction", BakeStage::Compress}},
      {"error_budget", {"--error-budget", BakeStage::Compress}},
      {"size_limit", {"--size-limit", BakeStage::Compress}},
      {"dump_matrices", {"--dump-matrices", BakeStage::None}},
      {"pictures", {"--no-pictures", BakeStage::None}},
  };
  return e;
}

// A valid value of `row` other than `v`.
SettingValue other_value(const SettingRow& row, const SettingValue& v) {
  switch (row.type) {
    case SettingType::Int: {
      const auto lo = static_cast<std::int64_t>(row.min), hi = static_cast<std::int64_t>(row.max);
      const auto* x = std::get_if<std::int64_t>(&v);
      if (!x || *x < lo) return lo + 1 <= hi ? lo + 1 : lo;
      return *x + 1 <= hi ? *x + 1 : lo;
    }
    case SettingType::Seed:
      return std::get<std::uint64_t>(v) + 1;
    case SettingType::Real: {
      const auto* x = std::get_if<double>(&v);
      return x ? (*x + row.min) / 2.0 + 0.01 : (row.min + row.max) / 2.0;
    }
    case SettingType::Flag:
      return !std::get<bool>(v);
    case SettingType::Choice:
      for (const SettingChoice& c : row.choices)
        if (v != SettingValue(std::string(c.name))) return std::string(c.name);
      break;
    case SettingType::Text:
      // The probe volumes' text must parse (runtime/probe_volume.h).
      if (std::string_view(row.name) == "light_probe_volumes")
        return std::string("0,0,0,1,1,1,0.5");
      return std::get<std::string>(v) + "/other";
  }
  ADD_FAILURE() << row.name << " has no other value";
  return v;
}

TEST(SettingsTable, ListsEverySettingWithItsOptionOnce) {
  std::map<std::string, int> seen;
  for (const SettingRow& row : settings_table()) {
    ++seen[row.name];
    const auto it = expected().find(row.name);
    ASSERT_NE(it, expected().end()) << "unexpected setting " << row.name;
    EXPECT_STREQ(row.flag, it->second.flag) << row.name;
    EXPECT_TRUE(row.help && *row.help) << row.name << " has no help";
    EXPECT_TRUE(row.manifest_key && *row.manifest_key) << row.name;
    EXPECT_EQ(&setting_row(row.name), &row);
  }
  EXPECT_EQ(seen.size(), expected().size());
  for (const auto& [name, count] : seen) EXPECT_EQ(count, 1) << name;
  EXPECT_THROW(setting_row("no_such_setting"), Error);
}

TEST(SettingsTable, EveryDefaultPassesValidate) {
  const BakeSettings defaults;
  EXPECT_NO_THROW(defaults.validate());
  for (const SettingRow& row : settings_table())
    EXPECT_NO_THROW(check_setting(row, row.get(defaults))) << row.name;
  // The defaults are what a user gets when they say nothing.
  EXPECT_EQ(setting_text(setting_row("bounces"), setting_row("bounces").get(defaults)), "auto");
  EXPECT_EQ(setting_text(setting_row("codec"), setting_row("codec").get(defaults)), "auto");
  EXPECT_EQ(setting_row("visibility_rays").get(defaults), SettingValue(std::int64_t{8}));
  EXPECT_EQ(setting_row("pictures").get(defaults), SettingValue(true));
}

// The error names the setting, never a front end's control for it.
void expect_rejected(const BakeSettings& s, const std::string& name) {
  try {
    s.validate();
    ADD_FAILURE() << name << ": validate() accepted the value";
  } catch (const BakeSettings::InvalidSetting& e) {
    EXPECT_EQ(e.setting(), name);
    const std::string what = e.what();
    EXPECT_NE(what.find("setting '" + name + "'"), std::string::npos) << what;
    EXPECT_EQ(what.find("--"), std::string::npos) << "names a CLI option: " << what;
  }
}

TEST(SettingsTable, OutOfRangeValuesNameTheSetting) {
  int rows_with_range = 0;
  for (const SettingRow& row : settings_table()) {
    if (row.type != SettingType::Int && row.type != SettingType::Real) continue;
    ++rows_with_range;
    const double below = row.min_exclusive ? row.min : row.min - 1.0;
    const double above = row.max_exclusive ? row.max : row.max + 1.0;
    for (const double bad : {below, above}) {
      BakeSettings s;
      if (row.type == SettingType::Int) {
        // Below the range may be a named value (bounces: 0 is auto); skip those.
        const auto v = static_cast<std::int64_t>(bad);
        bool is_named = false;
        for (const NamedValue& n : row.named) is_named = is_named || n.value == v;
        if (is_named) continue;
        row.set(s, v);
      } else {
        row.set(s, bad);
      }
      expect_rejected(s, row.name);
    }
  }
  EXPECT_EQ(rows_with_range, 15);
  // Spot checks against the documented ranges.
  BakeSettings s;
  s.error_budget = 1.0;
  expect_rejected(s, "error_budget");
  s = {};
  s.transport.bounces = 65;
  expect_rejected(s, "bounces");
  s = {};
  s.closure_rays = -1;
  expect_rejected(s, "closure_rays");
  s = {};
  s.closure_rays = 0;  // 0: no balancing
  EXPECT_NO_THROW(s.validate());
  // Combinations name the setting that does not apply.
  s = {};
  s.codec = CodecChoice::LargestEntries;
  s.error_budget = 0.1;
  expect_rejected(s, "error_budget");
  s = {};
  s.codec = CodecChoice::Dense;
  s.kept_fraction = 0.1;
  expect_rejected(s, "kept_fraction");
  s = {};
  s.kept_fraction = 0.1;
  s.size_limit = 0.5;
  expect_rejected(s, "size_limit");
}

TEST(SettingsTable, TextRoundTripsThroughParse) {
  const BakeSettings defaults;
  for (const SettingRow& row : settings_table()) {
    const SettingValue v = other_value(row, row.get(defaults));
    if (row.type == SettingType::Flag) continue;  // options without a value
    EXPECT_EQ(parse_setting(row, setting_text(row, v)), v) << row.name;
    BakeSettings s;
    row.set(s, v);
    EXPECT_EQ(row.get(s), v) << row.name;
  }
  const SettingRow& bounces = setting_row("bounces");
  EXPECT_EQ(parse_setting(bounces, "auto"), SettingValue(std::int64_t{0}));
  EXPECT_EQ(parse_setting(bounces, "inf"), SettingValue(std::int64_t{-1}));
  EXPECT_EQ(parse_setting(bounces, "infinity"), SettingValue(std::int64_t{-1}));
  EXPECT_EQ(parse_setting(bounces, "12"), SettingValue(std::int64_t{12}));
  for (const char* bad : {"0", "65", "3x", ""}) {
    try {
      parse_setting(bounces, bad);
      ADD_FAILURE() << "bounces accepted '" << bad << "'";
    } catch (const BakeSettings::InvalidSetting& e) {
      EXPECT_EQ(e.setting(), "bounces");
    }
  }
  EXPECT_EQ(parse_setting(setting_row("ordering"), "auto"), SettingValue());
  EXPECT_THROW(parse_setting(setting_row("codec"), "zip"), BakeSettings::InvalidSetting);
  EXPECT_THROW(parse_setting(setting_row("kept_fraction"), "0.1x"), BakeSettings::InvalidSetting);
}

const Scene& cornell_box() {
  static const Scene scene = [] {
    Diagnostics d;
    return SceneLoader(d).load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-box");
  }();
  return scene;
}

TEST(SettingsTable, RebakePlanReRunsFromEachRowsStage) {
  BakeSettings base;
  base.voxel_resolution = 3;
  base.codec = CodecChoice::LightWeighted;
  base.kept_fraction = 0.04;
  base.transport.bounces = 3;
  BakeSettings previous = base;
  previous.apply_scene_defaults(cornell_box().defaults);
  ASSERT_EQ(plan_rebake(cornell_box(), previous, base).first, BakeStage::None);
  for (const SettingRow& row : settings_table()) {
    const BakeStage want = expected().at(row.name).stage;
    EXPECT_EQ(row.stage, want) << row.name;
    // A patch target with a grid given changes nothing: the grid wins.
    if (std::string(row.name) == "patches_total") continue;
    BakeSettings next = base;
    row.set(next, other_value(row, row.get(previous)));
    const RebakePlan plan = plan_rebake(cornell_box(), previous, next);
    EXPECT_EQ(plan.first, want) << row.name;
    if (want != BakeStage::None) {
      ASSERT_EQ(plan.reasons.size(), 1u) << row.name;
      EXPECT_NE(plan.reasons[0].find(row.name == std::string("voxel_resolution")
                                         ? std::string("voxel resolution")
                                         : std::string(row.name)),
                std::string::npos)
          << plan.reasons[0];
    }
  }
}

}  // namespace
}  // namespace bounce
