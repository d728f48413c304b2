#pragma once
// Public: the bake settings and their table (one row per setting: name,
// type, default, range, help, manifest key, the stage a change re-runs),
// from which front ends build their controls.
//
//   for (const bounce::SettingRow& row : bounce::settings_table())
//     add_control(row.name, row.help, row.get(bounce::BakeSettings{}));
//   row.set(settings, bounce::parse_setting(row, text));  // throws InvalidSetting
#include "base/error.h"
#include "settings/bake_settings.h"
#include "settings/settings_table.h"
