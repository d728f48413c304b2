#include "settings_from_kwargs.h"

#include <string>

namespace py = pybind11;

namespace bounce::python {

namespace {

const SettingRow* find_row(const std::string& name) {
  for (const SettingRow& row : settings_table())
    if (name == row.name) return &row;
  return nullptr;
}

std::string known_names() {
  std::string names;
  for (const SettingRow& row : settings_table())
    names += (names.empty() ? "" : ", ") + std::string(row.name);
  return names;
}

// The value a Python object stands for in `row`: a bool for a flag, None
// to unset an optional setting, anything else read as the command line's
// text ("auto", 16, 0.02, "dense").
SettingValue value_for(const SettingRow& row, const py::handle& value) {
  const std::string name = row.name;
  if (value.is_none()) {
    if (!row.optional) throw py::value_error("setting '" + name + "': cannot be None");
    return std::monostate{};
  }
  const bool is_bool = py::isinstance<py::bool_>(value);
  if (row.type == SettingType::Flag) {
    if (!is_bool) throw py::value_error("setting '" + name + "': expected True or False");
    return value.cast<bool>();
  }
  if (is_bool) throw py::value_error("setting '" + name + "': is not a flag, got a bool");
  return parse_setting(row, py::str(value).cast<std::string>());
}

}  // namespace

BakeSettings settings_from_kwargs(const py::dict& kwargs) {
  BakeSettings settings;
  try {
    for (const auto& [key, value] : kwargs) {
      const std::string name = py::str(key).cast<std::string>();
      const SettingRow* row = find_row(name);
      if (!row)
        throw py::value_error("setting '" + name +
                              "': not a bake setting (the settings: " + known_names() + ")");
      row->set(settings, value_for(*row, value));
    }
    settings.validate();
  } catch (const BakeSettings::InvalidSetting& e) {
    throw py::value_error(e.what());
  }
  return settings;
}

}  // namespace bounce::python
