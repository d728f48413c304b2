#pragma once
// Core values as Python objects for the `bounce` module: float32 arrays of
// vectors and pictures, light lists, JSON as Python data. Each is a copy.
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "bounce/relight.h"
#include "bounce/scene.h"

namespace bounce::python {

// n x 3 float32 array.
pybind11::array_t<float> rows_of_three(const std::vector<glm::vec3>& v);
// height x width x 3 float32 array, top row first.
pybind11::array_t<float> picture(const RgbFloatImage& image);
// One dict per light: name, type, position, direction, color, intensity.
pybind11::list light_list(const std::vector<Light>& lights);
pybind11::object json_to_python(const nlohmann::json& value);

// Binds the Bake class (a bake folder opened for relighting) and open_bake.
void bind_opened_bake(pybind11::module_& m);

}  // namespace bounce::python
