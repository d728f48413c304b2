#pragma once
// scene.json, read and checked but not yet loaded: which mesh files to import
// with which transform, material definitions and overrides, lights, camera
// and bake defaults. Every key is documented in docs/scene-format.md.
// Internal to the scene module.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "base/diagnostics.h"
#include "scene/scene.h"

namespace bounce::scene_internal {

struct MaterialSpec {
  std::string key_path;  // where it was defined, for messages
  std::optional<glm::vec3> albedo;
  std::optional<glm::vec3> emission;
};

struct MeshSpec {
  std::string key_path;                 // "meshes[3]"
  std::filesystem::path file;           // resolved against the scene.json folder
  std::string name;                     // empty when not given
  glm::dmat4 transform{1.0};            // object -> scene, applied after the file's node transforms
  std::optional<std::string> material;  // every triangle gets this material
  bool two_sided = false;
  float patch_density = 1.0f;  // MeshInfo::patch_density
  // Densities of named objects of the file (the meshes it holds, by name),
  // in place of patch_density for those.
  std::map<std::string, float> object_density;
};

struct SceneDescription {
  std::vector<MeshSpec> meshes;
  // From `materials` and from inline mesh materials; names are unique.
  std::map<std::string, MaterialSpec> materials;
  std::vector<Light> lights;
  std::optional<Camera> camera;
  BakeDefaults defaults;
};

// Reads and validates `json_path`; throws SceneLoader::LoadError on anything
// fatal, warns in `diagnostics` about unknown and duplicate keys.
SceneDescription read_scene_json(const std::filesystem::path& json_path, Diagnostics& diagnostics);

}  // namespace bounce::scene_internal
