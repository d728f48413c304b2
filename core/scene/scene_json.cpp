#include "scene/scene_json.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/json_reader.h"
#include "scene/scene_loader.h"

namespace bounce::scene_internal {

namespace {

// Upper limits on bake defaults. They are not hard limits of the method but
// values no sensible scene asks for: the transport matrix is N x N, so a
// million patches would already need terabytes.
constexpr long long kMaxVoxelResolution = 4096;
constexpr long long kMaxPatchesTotal = 1'000'000;
constexpr long long kMaxPatchesPerVoxel = 1024;
constexpr long long kMaxSamplesPerFace = 65536;

std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw SceneLoader::LoadError(path.string(),
                                 std::string("cannot open for reading: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad())
    throw SceneLoader::LoadError(path.string(),
                                 std::string("cannot read: ") + std::strerror(errno));
  return text.str();
}

const Json* find(const Json& object, const char* key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

glm::dmat4 read_matrix(const JsonReader& r, const Json& value, const std::string& path) {
  const std::string expected = "expected 4 rows of 4 numbers (row-major), got ";
  if (!value.is_array() || value.size() != 4) r.fail(path, expected + JsonReader::describe(value));
  glm::dmat4 m(1.0);
  for (std::size_t row = 0; row < 4; ++row) {
    const std::string row_path = join_index(path, row);
    if (!value[row].is_array() || value[row].size() != 4)
      r.fail(row_path, "expected a row of 4 numbers, got " + JsonReader::describe(value[row]));
    for (std::size_t col = 0; col < 4; ++col)
      // glm is column-major: m[column][row].
      m[static_cast<glm::length_t>(col)][static_cast<glm::length_t>(row)] =
          r.number(value[row][col], join_index(row_path, col));
  }
  if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
    r.fail(join_index(path, 3), "the last row must be [0, 0, 0, 1] (an affine transform)");
  return m;
}

glm::dmat4 read_transform(const JsonReader& r, const Json& value, const std::string& path) {
  r.expect_object(value, path);
  r.warn_unknown_keys(value, path, {"translate", "rotate_deg", "scale", "matrix"});
  glm::dmat4 m(1.0);
  if (const Json* matrix = find(value, "matrix")) {
    if (value.contains("translate") || value.contains("rotate_deg") || value.contains("scale"))
      r.fail(path, "give either `matrix` or `translate`/`rotate_deg`/`scale`, not both");
    m = read_matrix(r, *matrix, join_key(path, "matrix"));
  } else {
    glm::dvec3 translate(0.0), rotate_deg(0.0), scale(1.0);
    if (const Json* t = find(value, "translate"))
      translate = r.vec3(*t, join_key(path, "translate"));
    if (const Json* rot = find(value, "rotate_deg"))
      rotate_deg = r.vec3(*rot, join_key(path, "rotate_deg"));
    if (const Json* s = find(value, "scale")) {
      const std::string scale_path = join_key(path, "scale");
      if (s->is_number())
        scale = glm::dvec3(r.number(*s, scale_path));
      else if (s->is_array())
        scale = r.vec3(*s, scale_path);
      else
        r.fail(scale_path,
               "expected a number or an array of 3 numbers, got " + JsonReader::describe(*s));
    }
    // Scale first, then rotate about X, then Y, then Z, then translate.
    m = glm::translate(m, translate);
    m = glm::rotate(m, glm::radians(rotate_deg.z), glm::dvec3(0, 0, 1));
    m = glm::rotate(m, glm::radians(rotate_deg.y), glm::dvec3(0, 1, 0));
    m = glm::rotate(m, glm::radians(rotate_deg.x), glm::dvec3(1, 0, 0));
    m = glm::scale(m, scale);
  }
  const double det = glm::determinant(glm::dmat3(m));
  if (!std::isfinite(det) || det == 0.0)
    r.fail(path, "is singular (determinant 0): it would flatten the mesh");
  return m;
}

glm::vec3 read_non_negative(const JsonReader& r, const Json& value, const std::string& path) {
  const glm::vec3 v = r.vec3_f(value, path);
  for (glm::length_t i = 0; i < 3; ++i)
    if (v[i] < 0.f) r.fail(path, "components must not be negative, got " + value.dump());
  return v;
}

// A material object; `allow_name` for inline materials, which may name themselves.
MaterialSpec read_material(const JsonReader& r, const Json& value, const std::string& path,
                           bool allow_name) {
  r.expect_object(value, path);
  if (allow_name)
    r.warn_unknown_keys(value, path, {"name", "albedo", "emission"});
  else
    r.warn_unknown_keys(value, path, {"albedo", "emission"});
  MaterialSpec spec;
  spec.key_path = path;
  // Albedo outside [0, 0.9999] is clamped later, with a warning, like albedo
  // from mesh files; only its type is checked here.
  if (const Json* a = find(value, "albedo")) spec.albedo = r.vec3_f(*a, join_key(path, "albedo"));
  if (const Json* e = find(value, "emission"))
    spec.emission = read_non_negative(r, *e, join_key(path, "emission"));
  return spec;
}

void read_materials(const JsonReader& r, const Json& value, SceneDescription& scene) {
  r.expect_object(value, "materials");
  for (const auto& item : value.items()) {
    const std::string path = join_key("materials", item.key());
    if (item.key().empty()) r.fail(path, "material names must not be empty");
    scene.materials[item.key()] = read_material(r, item.value(), path, false);
  }
}

MeshSpec read_mesh(const JsonReader& r, const Json& value, const std::string& path,
                   const std::filesystem::path& base_dir, SceneDescription& scene) {
  r.expect_object(value, path);
  r.warn_unknown_keys(
      value, path,
      {"file", "name", "transform", "material", "two_sided", "patch_density", "object_density"});
  MeshSpec mesh;
  mesh.key_path = path;
  const Json* file = find(value, "file");
  if (!file) r.fail(path, "missing key `file` (the mesh file, relative to scene.json)");
  const std::string file_name = r.string(*file, join_key(path, "file"));
  if (file_name.empty()) r.fail(join_key(path, "file"), "must not be empty");
  mesh.file = (base_dir / std::filesystem::path(file_name)).lexically_normal();
  if (const Json* n = find(value, "name")) mesh.name = r.string(*n, join_key(path, "name"));
  if (const Json* t = find(value, "transform"))
    mesh.transform = read_transform(r, *t, join_key(path, "transform"));
  if (const Json* two = find(value, "two_sided"))
    mesh.two_sided = r.boolean(*two, join_key(path, "two_sided"));
  // A patch density: a number in (0, kMaxPatchDensity].
  const auto density_at = [&r](const Json& d, const std::string& key) {
    if (!d.is_number())
      r.fail(key, "expected a number > 0 and <= " + std::to_string(kMaxPatchDensity) + ", got " +
                      JsonReader::describe(d));
    const double density = d.get<double>();
    // NaN fails both comparisons.
    if (!(density > 0.0 && density <= kMaxPatchDensity))
      r.fail(key, "must be a number > 0 and <= " + std::to_string(kMaxPatchDensity) +
                      " (a multiplier on the mesh's share of patches), got " + d.dump());
    return static_cast<float>(density);
  };
  if (const Json* d = find(value, "patch_density"))
    mesh.patch_density = density_at(*d, join_key(path, "patch_density"));
  if (const Json* objects = find(value, "object_density")) {
    const std::string key = join_key(path, "object_density");
    r.expect_object(*objects, key);
    for (const auto& [name, d] : objects->items()) {
      if (name.empty()) r.fail(key, "object names must not be empty");
      mesh.object_density[name] = density_at(d, key + "." + name);
    }
  }
  if (const Json* m = find(value, "material")) {
    const std::string mat_path = join_key(path, "material");
    if (m->is_string()) {
      mesh.material = m->get<std::string>();
      if (mesh.material->empty()) r.fail(mat_path, "material name must not be empty");
    } else if (m->is_object()) {
      MaterialSpec spec = read_material(r, *m, mat_path, true);
      std::string name = !mesh.name.empty() ? mesh.name : mesh.file.stem().string();
      if (const Json* n = find(*m, "name")) name = r.string(*n, join_key(mat_path, "name"));
      if (name.empty()) r.fail(join_key(mat_path, "name"), "material names must not be empty");
      if (const auto it = scene.materials.find(name); it != scene.materials.end())
        r.fail(mat_path, "material '" + name + "' is already defined at " + it->second.key_path +
                             "; give the inline material another `name`");
      scene.materials[name] = std::move(spec);
      mesh.material = name;
    } else {
      r.fail(mat_path,
             "expected a material name or a material object, got " + JsonReader::describe(*m));
    }
  }
  return mesh;
}

Light read_light(const JsonReader& r, const Json& value, const std::string& path,
                 std::size_t index) {
  r.expect_object(value, path);
  r.warn_unknown_keys(
      value, path,
      {"name", "type", "position", "direction", "color", "intensity", "inner_deg", "outer_deg"});
  Light light;
  light.name = "light" + std::to_string(index);
  if (const Json* n = find(value, "name")) light.name = r.string(*n, join_key(path, "name"));
  std::string type = "point";
  if (const Json* t = find(value, "type")) type = r.string(*t, join_key(path, "type"));
  if (const std::optional<Light::Type> t = light_type_from_name(type))
    light.type = *t;
  else
    r.fail(join_key(path, "type"),
           "expected \"point\", \"spot\" or \"directional\", got \"" + type + "\"");

  const Json* position = find(value, "position");
  if (position) {
    light.position = r.vec3_f(*position, join_key(path, "position"));
  } else if (light.type != Light::Type::Directional) {
    r.fail(path, "missing key `position` (a " + type + " light needs one)");
  }
  const Json* direction = find(value, "direction");
  if (direction) {
    const glm::dvec3 d = r.vec3(*direction, join_key(path, "direction"));
    if (glm::length(d) == 0.0)
      r.fail(join_key(path, "direction"),
             "is the zero vector; a " + type + " light needs a direction");
    light.direction = glm::vec3(glm::normalize(d));
  } else if (light.type != Light::Type::Point) {
    r.fail(path, "missing key `direction` (a " + type + " light needs one)");
  }
  if (const Json* c = find(value, "color"))
    light.color = read_non_negative(r, *c, join_key(path, "color"));
  if (const Json* i = find(value, "intensity")) {
    light.intensity = r.number_f(*i, join_key(path, "intensity"));
    if (light.intensity < 0.f)
      r.fail(join_key(path, "intensity"), "must not be negative, got " + i->dump());
  }
  if (const Json* inner = find(value, "inner_deg"))
    light.spot_inner_deg = r.number_f(*inner, join_key(path, "inner_deg"));
  if (const Json* outer = find(value, "outer_deg"))
    light.spot_outer_deg = r.number_f(*outer, join_key(path, "outer_deg"));
  if (light.type == Light::Type::Spot) {
    if (!(light.spot_outer_deg > 0.f && light.spot_outer_deg <= 180.f))
      r.fail(join_key(path, "outer_deg"),
             "must be in (0, 180] degrees, got " + std::to_string(light.spot_outer_deg));
    if (!(light.spot_inner_deg >= 0.f && light.spot_inner_deg <= light.spot_outer_deg))
      r.fail(join_key(path, "inner_deg"), "must be in [0, outer_deg] = [0, " +
                                              std::to_string(light.spot_outer_deg) + "], got " +
                                              std::to_string(light.spot_inner_deg));
  }
  return light;
}

Camera read_camera(const JsonReader& r, const Json& value) {
  const std::string path = "camera";
  r.expect_object(value, path);
  r.warn_unknown_keys(value, path, {"position", "target", "up", "fov_y_deg"});
  Camera camera;
  const Json* position = find(value, "position");
  const Json* target = find(value, "target");
  if (!position) r.fail(path, "missing key `position`");
  if (!target) r.fail(path, "missing key `target`");
  camera.position = r.vec3_f(*position, "camera.position");
  camera.target = r.vec3_f(*target, "camera.target");
  if (const Json* up = find(value, "up")) camera.up = r.vec3_f(*up, "camera.up");
  if (const Json* fov = find(value, "fov_y_deg")) {
    camera.fov_y_deg = r.number_f(*fov, "camera.fov_y_deg");
    if (!(camera.fov_y_deg > 0.f && camera.fov_y_deg < 180.f))
      r.fail("camera.fov_y_deg", "must be in (0, 180) degrees, got " + fov->dump());
  }
  const glm::dvec3 view = glm::dvec3(camera.target) - glm::dvec3(camera.position);
  if (glm::length(view) == 0.0) r.fail(path, "`position` and `target` are the same point");
  const glm::dvec3 up(camera.up);
  if (glm::length(glm::cross(view, up)) <= 1e-9 * glm::length(view) * glm::length(up))
    r.fail("camera.up", "is zero or parallel to the view direction");
  return camera;
}

std::optional<int> read_count(const JsonReader& r, const Json& bake, const char* key,
                              long long max) {
  const Json* value = find(bake, key);
  if (!value) return std::nullopt;
  return static_cast<int>(r.integer(*value, join_key("bake", key), 1, max));
}

// "on", "volumes" or "off" (true and false stand for on and off).
std::string read_probe_switch(const JsonReader& r, const Json& value) {
  const std::string path = "bake.light_probes";
  if (value.is_boolean()) return value.get<bool>() ? "on" : "off";
  const std::string s = r.string(value, path);
  if (s != "on" && s != "volumes" && s != "off")
    r.fail(path, "must be \"on\", \"volumes\", \"off\", true or false, got " +
                     JsonReader::describe(value));
  return s;
}

// {"min": [x, y, z], "max": [x, y, z], "spacing": s} as the setting's text
// "x0,y0,z0,x1,y1,z1,s" (runtime/probe_volume.h).
std::string read_probe_volume(const JsonReader& r, const Json& value, const std::string& path) {
  r.expect_object(value, path);
  r.warn_unknown_keys(value, path, {"min", "max", "spacing"});
  const auto required = [&](const char* key) -> const Json& {
    const Json* v = find(value, key);
    if (!v) r.fail(join_key(path, key), "missing; a probe volume has min, max and spacing");
    return *v;
  };
  const glm::vec3 lo = r.vec3_f(required("min"), join_key(path, "min"));
  const glm::vec3 hi = r.vec3_f(required("max"), join_key(path, "max"));
  const float spacing = r.number_f(required("spacing"), join_key(path, "spacing"));
  for (int a = 0; a < 3; ++a)
    if (!(lo[a] < hi[a])) r.fail(path, "`min` must be below `max` on every axis");
  if (!(spacing > 0.0f))
    r.fail(join_key(path, "spacing"), "must be positive, got " + std::to_string(spacing));
  char text[256];
  std::snprintf(text, sizeof text, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", lo.x, lo.y, lo.z, hi.x,
                hi.y, hi.z, spacing);
  return text;
}

std::string read_probe_volumes(const JsonReader& r, const Json& value) {
  const std::string path = "bake.light_probe_volumes";
  r.expect_array(value, path);
  std::string text;
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (!text.empty()) text += ';';
    text += read_probe_volume(r, value[i], join_index(path, i));
  }
  return text;
}

BakeDefaults read_bake(const JsonReader& r, const Json& value) {
  r.expect_object(value, "bake");
  r.warn_unknown_keys(value, "bake",
                      {"voxel", "patches_total", "patches_per_voxel", "samples_per_face",
                       "error_budget", "light_probes", "light_probe_volumes"});
  BakeDefaults d;
  d.voxel_resolution = read_count(r, value, "voxel", kMaxVoxelResolution);
  d.patches_total = read_count(r, value, "patches_total", kMaxPatchesTotal);
  d.patches_per_voxel = read_count(r, value, "patches_per_voxel", kMaxPatchesPerVoxel);
  d.samples_per_face = read_count(r, value, "samples_per_face", kMaxSamplesPerFace);
  if (const Json* budget = find(value, "error_budget")) {
    d.error_budget = r.number_f(*budget, "bake.error_budget");
    if (!(*d.error_budget > 0.0 && *d.error_budget < 1.0))
      r.fail("bake.error_budget",
             "must be a relative error between 0 and 1 (exclusive), got " + budget->dump());
  }
  if (const Json* probes = find(value, "light_probes"))
    d.light_probes = read_probe_switch(r, *probes);
  if (const Json* volumes = find(value, "light_probe_volumes"))
    d.light_probe_volumes = read_probe_volumes(r, *volumes);
  return d;
}

}  // namespace

SceneDescription read_scene_json(const std::filesystem::path& json_path, Diagnostics& diagnostics) {
  const JsonReader r(json_path.string(), diagnostics);
  const Json root = r.parse(read_text_file(json_path));
  if (!root.is_object())
    r.fail("", "the top level must be an object, got " + JsonReader::describe(root));
  r.warn_unknown_keys(root, "", {"description", "meshes", "materials", "lights", "camera", "bake"});

  SceneDescription scene;
  if (const Json* d = find(root, "description")) r.string(*d, "description");
  if (const Json* m = find(root, "materials")) read_materials(r, *m, scene);

  const Json* meshes = find(root, "meshes");
  if (!meshes) r.fail("meshes", "missing; a scene needs at least one mesh");
  r.expect_array(*meshes, "meshes");
  if (meshes->empty()) r.fail("meshes", "is empty; a scene needs at least one mesh");
  const std::filesystem::path base_dir = json_path.parent_path();
  for (std::size_t i = 0; i < meshes->size(); ++i)
    scene.meshes.push_back(read_mesh(r, (*meshes)[i], join_index("meshes", i), base_dir, scene));

  if (const Json* lights = find(root, "lights")) {
    r.expect_array(*lights, "lights");
    for (std::size_t i = 0; i < lights->size(); ++i)
      scene.lights.push_back(read_light(r, (*lights)[i], join_index("lights", i), i));
  }
  if (const Json* camera = find(root, "camera")) scene.camera = read_camera(r, *camera);
  if (const Json* bake = find(root, "bake")) scene.defaults = read_bake(r, *bake);
  return scene;
}

}  // namespace bounce::scene_internal
