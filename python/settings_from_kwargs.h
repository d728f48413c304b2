#pragma once
// Bake settings from Python keyword arguments, by the settings table's names
// (voxel_resolution=16, codec="dense"). Every value goes through the table:
// a name that is not a setting or a value its row refuses raises ValueError
// naming the setting.
#include <pybind11/pybind11.h>

#include "bounce/settings.h"

namespace bounce::python {

// `kwargs` holds only setting names. Throws pybind11::value_error.
BakeSettings settings_from_kwargs(const pybind11::dict& kwargs);

}  // namespace bounce::python
