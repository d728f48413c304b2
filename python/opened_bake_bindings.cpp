// The `bounce.Bake` class: a bake folder opened for relighting
// (opened_bake.h), its properties and the frames it lights.
#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "opened_bake.h"
#include "python_values.h"

namespace py = pybind11;

namespace bounce::python {

namespace {

// The lit mesh, built without the GIL on first use.
const LitMesh& mesh_of(OpenedBake& b) {
  py::gil_scoped_release release;
  return b.mesh();
}

py::array_t<std::uint32_t> triangles_of(OpenedBake& b) {
  const LitMesh& mesh = mesh_of(b);
  py::array_t<std::uint32_t> a({static_cast<py::ssize_t>(mesh.triangles.size()), py::ssize_t{3}});
  std::uint32_t* out = a.mutable_data();
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) out[3 * i + k] = mesh.triangles[i][k];
  return a;
}

py::dict relight_frame(OpenedBake& b,
                       const std::optional<std::map<std::string, std::array<float, 3>>>& lights) {
  std::map<std::string, glm::vec3> moved;
  if (lights)
    for (const auto& [name, p] : *lights) moved[name] = glm::vec3(p[0], p[1], p[2]);
  RelitFrame frame;
  {
    py::gil_scoped_release release;
    frame = b.relight(moved);
  }
  py::dict out;
  out["first_hit"] = rows_of_three(frame.first_hit);
  out["indirect"] = rows_of_three(frame.indirect);
  out["patch_light"] = rows_of_three(frame.reflected);
  out["exitance"] = rows_of_three(frame.exitance);
  out["vertex_light"] = rows_of_three(frame.vertex_light);
  py::array_t<float> sh({static_cast<py::ssize_t>(frame.probe_sh.size() / kShCoefficients),
                         static_cast<py::ssize_t>(kShCoefficients), py::ssize_t{3}});
  std::copy_n(reinterpret_cast<const float*>(frame.probe_sh.data()), 3 * frame.probe_sh.size(),
              sh.mutable_data());
  out["probe_sh"] = sh;
  return out;
}

py::array_t<float> probe_sh_at_point(OpenedBake& b, const std::array<float, 3>& point) {
  std::array<glm::vec3, kShCoefficients> sh;
  {
    py::gil_scoped_release release;
    sh = b.probe_sh_at(glm::vec3(point[0], point[1], point[2]));
  }
  py::array_t<float> out({static_cast<py::ssize_t>(kShCoefficients), py::ssize_t{3}});
  std::copy_n(reinterpret_cast<const float*>(sh.data()), 3 * kShCoefficients, out.mutable_data());
  return out;
}

py::dict camera_pictures(OpenedBake& b, int width, int height, int samples, int gather_rays) {
  CameraImageSettings settings;
  settings.width = width;
  settings.height = height;
  settings.samples_per_side = samples;
  CameraImages images;
  {
    py::gil_scoped_release release;
    images = b.camera_images(settings, gather_rays);
  }
  py::dict out;
  out["direct"] = picture(images.direct);
  out["indirect"] = picture(images.indirect);
  out["full"] = picture(images.full);
  py::array_t<float> coverage({static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width)});
  std::copy(images.coverage.begin(), images.coverage.end(), coverage.mutable_data());
  out["coverage"] = coverage;
  return out;
}

void bind_properties(py::class_<OpenedBake>& c) {
  c.def_property_readonly("patch_count", &OpenedBake::patch_count)
      .def_property_readonly("lights",
                             [](const OpenedBake& b) { return light_list(b.scene().lights); })
      .def_property_readonly("multiply", &OpenedBake::multiply_name)
      .def_property_readonly("has_final_gather", &OpenedBake::has_final_gather)
      .def_property_readonly(
          "probe_positions", [](const OpenedBake& b) { return rows_of_three(b.probe_positions()); },
          "The light probes' positions (probes x 3, float32; 0 x 3 for a bake without them)")
      .def_property_readonly("manifest",
                             [](const OpenedBake& b) { return json_to_python(b.bake().manifest); })
      .def_property_readonly("vertex_positions",
                             [](OpenedBake& b) { return rows_of_three(mesh_of(b).positions); })
      .def_property_readonly("triangles", &triangles_of);
}

void bind_frames(py::class_<OpenedBake>& c) {
  c.def("relight", &relight_frame, py::arg("lights") = py::none(),
        "relight(lights=None) -> dict of float32 arrays.\n"
        "One frame with the scene's lights; lights={'name': (x, y, z)} moves point and spot "
        "lights first. Per patch (n x 3): first_hit (b), indirect (T b), patch_light "
        "(b + T b), exitance (emission + b + T b); per lit-mesh vertex (v x 3): vertex_light; "
        "per light probe (p x 9 x 3, p = 0 without probes): probe_sh, the irradiance of light "
        "reflected at least once as real SH L2 (docs/bake-format.md, Light probes).")
      .def("probe_sh_at", &probe_sh_at_point, py::arg("point"),
           "probe_sh_at(point) -> float32 array 9 x 3.\n"
           "The irradiance SH at point (x, y, z) in the empty space, in the last frame "
           "(relight() or camera_image(); before either, the scene's own lights): the light "
           "probes around it that see it, blended trilinearly by distance, so no light crosses "
           "a wall; row j is coefficient j (R, G, B) of light reflected at least once as real "
           "SH L2 (docs/bake-format.md, Light probes). All zero when no probe within two voxels "
           "sees the point. Raises for a bake without probes.")
      .def("camera_image", &camera_pictures, py::arg("width") = 320, py::arg("height") = 240,
           py::arg("samples") = 1, py::arg("gather_rays") = 256,
           "camera_image(width=320, height=240, samples=1, gather_rays=256) -> dict of float32 "
           "arrays.\n"
           "The scene camera's pictures under the scene's own lights, as `bounce solve` renders "
           "them (samples x samples rays per pixel; each pixel gathers from the patches it sees "
           "with gather_rays rays, 0: from the nearest patches): direct, indirect and full "
           "(height x width x 3, linear light, top row first) and coverage (height x width: the "
           "share of a pixel's rays that hit the scene).");
}

}  // namespace

void bind_opened_bake(py::module_& m) {
  py::class_<OpenedBake> c(m, "Bake", "A bake folder opened for relighting");
  bind_properties(c);
  bind_frames(c);
  m.def(
      "open_bake",
      [](const std::string& folder, const std::string& scene) {
        py::gil_scoped_release release;
        return std::make_unique<OpenedBake>(folder, scene);
      },
      py::arg("folder"), py::arg("scene") = "",
      "Opens a bake folder for relighting; scene: the scene path when the manifest's is gone.");
}

}  // namespace bounce::python
