#include "scene/scene_loader.h"

#include <algorithm>
#include <cctype>
#include <system_error>

#include "scene/mesh_import.h"
#include "scene/scene_builder.h"
#include "scene/scene_defaults.h"
#include "scene/scene_json.h"

namespace bounce {

namespace {

namespace fs = std::filesystem;
using namespace scene_internal;

std::string lower_extension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// `referenced_by` says where the path came from, for the message.
void require_regular_file(const fs::path& path, const std::string& referenced_by) {
  std::error_code ec;
  const auto status = fs::status(path, ec);
  const std::string suffix = referenced_by.empty() ? "" : " (" + referenced_by + ")";
  if (!fs::exists(status)) throw SceneLoader::LoadError(path.string(), "no such file" + suffix);
  if (!fs::is_regular_file(status))
    throw SceneLoader::LoadError(path.string(), "not a regular file" + suffix);
}

void warn_if_dark(const Scene& scene, Diagnostics& diagnostics) {
  if (!scene.lights.empty()) return;
  for (const Material& m : scene.materials)
    if (m.is_emissive()) return;  // builder keeps only materials that triangles use
  diagnostics.warn(scene.path, "no lights and no emissive surfaces: the bake will be dark");
}

Scene load_scene_json(const fs::path& json, Diagnostics& diagnostics) {
  SceneDescription description = read_scene_json(json, diagnostics);
  SceneBuilder builder(json.string(), description.materials, diagnostics);
  for (const MeshSpec& mesh : description.meshes) {
    require_regular_file(mesh.file, mesh.key_path + ".file in " + json.string());
    builder.add(import_mesh_file(mesh.file, mesh.transform, mesh.name, diagnostics), mesh.two_sided,
                mesh.material, mesh.key_path, mesh.patch_density, mesh.object_density);
  }
  Scene scene;
  scene.name = fs::absolute(json).parent_path().filename().string();
  scene.path = json.string();
  builder.build(scene);
  scene.lights = std::move(description.lights);
  scene.camera = description.camera ? *description.camera : default_camera(scene.bounds());
  scene.defaults = description.defaults;
  return scene;
}

Scene load_bare_mesh(const fs::path& file, Diagnostics& diagnostics) {
  SceneBuilder builder(file.string(), {}, diagnostics);
  builder.add(import_mesh_file(file, glm::dmat4(1.0), "", diagnostics), false, std::nullopt, "");
  Scene scene;
  scene.name = file.stem().string();
  scene.path = file.string();
  builder.build(scene);
  const Bounds bounds = scene.bounds();
  scene.lights.push_back(default_light(bounds));
  scene.camera = default_camera(bounds);
  return scene;
}

}  // namespace

Scene SceneLoader::load(const std::filesystem::path& path) const {
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (!fs::exists(status)) throw LoadError(path.string(), "no such file or folder");
  fs::path file = path;
  if (fs::is_directory(status)) {
    file = path / "scene.json";
    if (!fs::exists(file, ec))
      throw LoadError(path.string(),
                      "folder has no scene.json (give a scene folder, a "
                      "scene.json or a mesh file)");
  }
  require_regular_file(file, "");
  Scene scene = lower_extension(file) == ".json" ? load_scene_json(file, diagnostics_)
                                                 : load_bare_mesh(file, diagnostics_);
  warn_if_dark(scene, diagnostics_);
  return scene;
}

}  // namespace bounce
