#pragma once
// Turns imported mesh files plus scene.json material definitions into the
// Scene's flat triangle soup (with the files' per-vertex colours per
// triangle corner): one material table by name (file colours,
// overridden by scene.json), albedo defaulted or clamped with a warning,
// degenerate and duplicate triangles counted and skipped with one warning
// per kind and file (naming the first few meshes), textures read once each, and
// only the vertices that kept triangles use. Internal to the scene module.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/diagnostics.h"
#include "scene/mesh_import.h"
#include "scene/scene.h"
#include "scene/scene_json.h"

namespace bounce::scene_internal {

class SceneBuilder {
 public:
  // `scene_file` is what scene-wide errors name (the scene.json or bare mesh);
  // `definitions` are the scene.json materials (empty for a bare mesh).
  SceneBuilder(std::string scene_file, std::map<std::string, MaterialSpec> definitions,
               Diagnostics& diagnostics);

  // `material` overrides the file's materials for every triangle of it;
  // `key_path` ("meshes[2]") names the scene.json entry in messages;
  // `patch_density` goes to every mesh of the file (MeshInfo::patch_density).
  void add(ImportedFile file, bool two_sided, std::optional<std::string> material,
           std::string key_path, float patch_density = 1.0f,
           std::map<std::string, float> object_density = {});

  // Fills geometry, materials and meshes of `scene`. Throws
  // SceneLoader::LoadError when no triangle is left or a material is unknown.
  void build(Scene& scene);

 private:
  struct Entry {
    ImportedFile file;
    bool two_sided;
    std::optional<std::string> material;
    std::string key_path;
    float patch_density;
    std::map<std::string, float> object_density;
  };

  std::uint32_t material_index(const std::string& name, const Entry& entry,
                               const ImportedMaterial* from_file);
  // The images a material's files name, read (null: none, or unreadable).
  struct MaterialImages {
    std::shared_ptr<const Texture> texture, emission, normal_map;
    std::shared_ptr<const AlphaMask> mask;
  };
  Material resolve_material(const std::string& name, MaterialImages images) const;

  std::string scene_file_;
  std::map<std::string, MaterialSpec> definitions_;
  Diagnostics& diagnostics_;
  std::vector<Entry> entries_;

  // Materials in order of first use, with what the files said about them.
  struct Use {
    std::string name;
    std::optional<ImportedMaterial> from_file;
    std::string file;     // where from_file came from
    std::string used_by;  // first scene.json entry or file that used it
  };
  std::vector<Use> uses_;
  std::map<std::string, std::uint32_t> use_index_;
};

}  // namespace bounce::scene_internal
