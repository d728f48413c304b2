// The `bounce` Python module: load a scene, bake it into a bake folder and
// relight a bake, through the same public core functions the CLI and the
// studio call (docs/python.md).
#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bounce/bake.h"
#include "bounce/blas.h"
#include "bounce/scene.h"
#include "opened_bake.h"
#include "progress_callback.h"
#include "settings_from_kwargs.h"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace bounce::python {

namespace {

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

// A loaded scene, shared by the bakes made from it.
struct PyScene {
  std::shared_ptr<const Scene> scene;
  std::vector<std::string> warnings;
};

PyScene load_scene(const std::string& path) {
  Diagnostics diagnostics;
  PyScene out;
  {
    py::gil_scoped_release release;
    out.scene = std::make_shared<const Scene>(SceneLoader(diagnostics).load(path));
  }
  for (const Diagnostic& d : diagnostics.all())
    if (d.kind == Diagnostic::Kind::Warning) out.warnings.push_back(d.where + ": " + d.message);
  return out;
}

py::object bake(const py::object& scene_or_path, const std::string& out_dir, py::kwargs kwargs) {
  py::object callable = py::none();
  py::dict settings_kwargs;
  for (const auto& [key, value] : kwargs) {
    if (py::str(key).cast<std::string>() == "progress")
      callable = py::reinterpret_borrow<py::object>(value);
    else
      settings_kwargs[key] = value;
  }
  const BakeSettings settings = settings_from_kwargs(settings_kwargs);
  std::shared_ptr<const Scene> scene;
  if (py::isinstance<PyScene>(scene_or_path))
    scene = scene_or_path.cast<const PyScene&>().scene;
  else
    scene = load_scene(py::str(scene_or_path).cast<std::string>()).scene;
  ProgressCallback progress(std::move(callable));
  nlohmann::json manifest;
  try {
    py::gil_scoped_release release;
    Diagnostics diagnostics;
    const BakeResult result = Baker(*scene, settings, diagnostics).run(progress.progress());
    manifest = write_bake(out_dir, *scene, result, diagnostics);
  } catch (const Cancelled&) {
    progress.rethrow_if_raised();
    throw;
  }
  return json_to_python(manifest);
}

}  // namespace

}  // namespace bounce::python

PYBIND11_MODULE(bounce, m) {
  using namespace bounce;
  using namespace bounce::python;
  m.doc() = "Bounce: bake a scene's radiosity transport and relight the bake (docs/python.md)";
  // At import, before a bake or a relighter can run BLAS on another thread.
  choose_blas_kernels();

  // The exception types live as long as the interpreter: never released, so
  // that no reference is dropped after Python has shut down.
  static const auto* error = new py::exception<Error>(m, "Error", PyExc_RuntimeError);
  static const auto* cancelled = new py::exception<Cancelled>(m, "Cancelled", error->ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const BakeSettings::InvalidSetting& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const Cancelled& e) {
      PyErr_SetString(cancelled->ptr(), e.what());
    } catch (const Error& e) {
      PyErr_SetString(error->ptr(), e.what());
    }
  });

  py::class_<PyScene>(m, "Scene", "A scene as the core loaded it")
      .def_property_readonly("name", [](const PyScene& s) { return s.scene->name; })
      .def_property_readonly("triangle_count",
                             [](const PyScene& s) { return s.scene->triangle_count(); })
      .def_property_readonly("mesh_count", [](const PyScene& s) { return s.scene->meshes.size(); })
      .def_property_readonly("lights", [](const PyScene& s) { return light_list(s.scene->lights); })
      .def_property_readonly("warnings", [](const PyScene& s) { return s.warnings; })
      .def("__repr__", [](const PyScene& s) {
        return "<bounce.Scene '" + s.scene->name +
               "': " + std::to_string(s.scene->triangle_count()) + " triangles, " +
               std::to_string(s.scene->lights.size()) + " lights>";
      });

  m.def("load_scene", &load_scene, py::arg("path"),
        "Loads a scene folder, scene.json or mesh file; raises bounce.Error naming the file.");

  m.def(
      "settings",
      []() {
        py::list out;
        for (const SettingRow& row : settings_table()) {
          py::dict d;
          d["name"] = row.name;
          d["default"] = setting_text(row, row.get(BakeSettings{}));
          d["help"] = row.help;
          out.append(d);
        }
        return out;
      },
      "The bake settings: name, default (as text) and help, one dict each.");

  m.def("bake", &bake, py::arg("scene"), py::arg("out_dir"),
        "bake(scene, out_dir, progress=None, **settings) -> manifest dict.\n"
        "Bakes a Scene (or a scene path) into the bake folder out_dir, as `bounce bake` does. "
        "Settings by the settings table's names (voxel_resolution=16, codec='dense'); a bad "
        "name or value raises ValueError naming it. progress(stage, fraction) returning False "
        "cancels: bounce.Cancelled is raised and no folder is left behind.");

  py::class_<OpenedBake>(m, "Bake", "A bake folder opened for relighting")
      .def_property_readonly("patch_count", &OpenedBake::patch_count)
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
                             [](OpenedBake& b) {
                               const LitMesh* mesh = nullptr;
                               {
                                 py::gil_scoped_release release;
                                 mesh = &b.mesh();
                               }
                               return rows_of_three(mesh->positions);
                             })
      .def_property_readonly(
          "triangles",
          [](OpenedBake& b) {
            const LitMesh* mesh = nullptr;
            {
              py::gil_scoped_release release;
              mesh = &b.mesh();
            }
            py::array_t<std::uint32_t> a(
                {static_cast<py::ssize_t>(mesh->triangles.size()), py::ssize_t{3}});
            std::uint32_t* out = a.mutable_data();
            for (std::size_t i = 0; i < mesh->triangles.size(); ++i)
              for (int k = 0; k < 3; ++k) out[3 * i + k] = mesh->triangles[i][k];
            return a;
          })
      .def(
          "relight",
          [](OpenedBake& b,
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
            py::array_t<float> sh(
                {static_cast<py::ssize_t>(frame.probe_sh.size() / kShCoefficients),
                 static_cast<py::ssize_t>(kShCoefficients), py::ssize_t{3}});
            std::copy_n(reinterpret_cast<const float*>(frame.probe_sh.data()),
                        3 * frame.probe_sh.size(), sh.mutable_data());
            out["probe_sh"] = sh;
            return out;
          },
          py::arg("lights") = py::none(),
          "relight(lights=None) -> dict of float32 arrays.\n"
          "One frame with the scene's lights; lights={'name': (x, y, z)} moves point and spot "
          "lights first. Per patch (n x 3): first_hit (b), indirect (T b), patch_light "
          "(b + T b), exitance (emission + b + T b); per lit-mesh vertex (v x 3): vertex_light; "
          "per "
          "light probe (p x 9 x 3, p = 0 without probes): probe_sh, the irradiance of light "
          "reflected at least once as real SH L2 (docs/bake-format.md, Light probes).")
      .def(
          "probe_sh_at",
          [](OpenedBake& b, const std::array<float, 3>& point) {
            std::array<glm::vec3, kShCoefficients> sh;
            {
              py::gil_scoped_release release;
              sh = b.probe_sh_at(glm::vec3(point[0], point[1], point[2]));
            }
            py::array_t<float> out({static_cast<py::ssize_t>(kShCoefficients), py::ssize_t{3}});
            std::copy_n(reinterpret_cast<const float*>(sh.data()), 3 * kShCoefficients,
                        out.mutable_data());
            return out;
          },
          py::arg("point"),
          "probe_sh_at(point) -> float32 array 9 x 3.\n"
          "The irradiance SH at point (x, y, z) in the empty space, in the last frame "
          "(relight() or camera_image(); before either, the scene's own lights): the light "
          "probes around it that see it, blended trilinearly by distance, so no light crosses "
          "a wall; row j is coefficient j (R, G, B) of light reflected at least once as real "
          "SH L2 (docs/bake-format.md, Light probes). All zero when no probe within two voxels "
          "sees the point. Raises for a bake without probes.")
      .def(
          "camera_image",
          [](OpenedBake& b, int width, int height, int samples, int gather_rays) {
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
            py::array_t<float> coverage(
                {static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width)});
            std::copy(images.coverage.begin(), images.coverage.end(), coverage.mutable_data());
            out["coverage"] = coverage;
            return out;
          },
          py::arg("width") = 320, py::arg("height") = 240, py::arg("samples") = 1,
          py::arg("gather_rays") = 256,
          "camera_image(width=320, height=240, samples=1, gather_rays=256) -> dict of float32 "
          "arrays.\n"
          "The scene camera's pictures under the scene's own lights, as `bounce solve` renders "
          "them (samples x samples rays per pixel; each pixel gathers from the patches it sees "
          "with gather_rays rays, 0: from the nearest patches): direct, indirect and full "
          "(height x width x 3, linear light, top row first) and coverage (height x width: the "
          "share of a pixel's rays that hit the scene).");

  m.def(
      "open_bake",
      [](const std::string& folder, const std::string& scene) {
        py::gil_scoped_release release;
        return std::make_unique<OpenedBake>(folder, scene);
      },
      py::arg("folder"), py::arg("scene") = "",
      "Opens a bake folder for relighting; scene: the scene path when the manifest's is gone.");
  m.def(
      "is_bake_folder", [](const std::string& folder) { return is_bake_folder(folder); },
      py::arg("folder"));
}
