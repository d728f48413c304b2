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
#include "python_values.h"
#include "settings_from_kwargs.h"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace bounce::python {

namespace {

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

// Bounce's errors as Python exceptions: bounce.Error (a RuntimeError),
// bounce.Cancelled (an Error), and ValueError for a bad setting.
void bind_errors(py::module_& m) {
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
}

void bind_scene(py::module_& m) {
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
}

void bind_bake(py::module_& m) {
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

  m.def(
      "is_bake_folder", [](const std::string& folder) { return is_bake_folder(folder); },
      py::arg("folder"));
}

}  // namespace

}  // namespace bounce::python

PYBIND11_MODULE(bounce, m) {
  using namespace bounce::python;
  m.doc() = "Bounce: bake a scene's radiosity transport and relight the bake (docs/python.md)";
  // At import, before a bake or a relighter can run BLAS on another thread.
  bounce::choose_blas_kernels();
  bind_errors(m);
  bind_scene(m);
  bind_bake(m);
  bind_opened_bake(m);
}
