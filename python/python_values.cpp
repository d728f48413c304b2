#include "python_values.h"

namespace py = pybind11;

namespace bounce::python {

// n x 3 float32 array holding a copy of `v`.
py::array_t<float> rows_of_three(const std::vector<glm::vec3>& v) {
  py::array_t<float> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  float* out = a.mutable_data();
  for (std::size_t i = 0; i < v.size(); ++i) {
    out[3 * i] = v[i].x;
    out[3 * i + 1] = v[i].y;
    out[3 * i + 2] = v[i].z;
  }
  return a;
}

// height x width x 3 float32 array holding a copy of `image` (top row first).
py::array_t<float> picture(const RgbFloatImage& image) {
  py::array_t<float> a({static_cast<py::ssize_t>(image.height),
                        static_cast<py::ssize_t>(image.width), py::ssize_t{3}});
  float* out = a.mutable_data();
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    out[3 * i] = image.pixels[i].x;
    out[3 * i + 1] = image.pixels[i].y;
    out[3 * i + 2] = image.pixels[i].z;
  }
  return a;
}

py::list light_list(const std::vector<Light>& lights) {
  py::list out;
  for (const Light& l : lights) {
    py::dict d;
    d["name"] = l.name;
    d["type"] = light_type_name(l.type);
    d["position"] = py::make_tuple(l.position.x, l.position.y, l.position.z);
    d["direction"] = py::make_tuple(l.direction.x, l.direction.y, l.direction.z);
    d["color"] = py::make_tuple(l.color.x, l.color.y, l.color.z);
    d["intensity"] = l.intensity;
    out.append(d);
  }
  return out;
}

py::object json_to_python(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

}  // namespace bounce::python
