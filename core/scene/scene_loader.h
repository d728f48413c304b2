#pragma once
// Loads a scene: either a scene.json (meshes with transforms, materials,
// lights, camera, bake defaults; see docs/scene-format.md) or a bare mesh file
// (OBJ+MTL, PLY, glTF, anything Assimp reads) with default lights and camera
// derived from its bounding box. Meshes are read with Assimp so diffuse (Kd)
// and emissive (Ke) colours arrive as exact floats.
//
// Validation: one LoadError naming the file and what is wrong for fatal
// problems (missing file, malformed JSON with line/column, NaN/Inf vertices,
// no geometry left, absurd bake defaults); warnings in Diagnostics for what is
// repaired (unknown keys, degenerate or zero-area triangles skipped and
// counted, materials without albedo given the default).
#include <filesystem>

#include "base/diagnostics.h"
#include "base/error.h"
#include "scene/scene.h"

namespace bounce {

class SceneLoader {
 public:
  class LoadError : public Error {
   public:
    using Error::Error;
  };

  // Albedo given to materials that do not say theirs.
  static constexpr float kDefaultAlbedo = 0.5f;

  explicit SceneLoader(Diagnostics& diagnostics) : diagnostics_(diagnostics) {}

  // `path` is a scene.json, a folder holding one, or a mesh file.
  Scene load(const std::filesystem::path& path) const;

 private:
  Diagnostics& diagnostics_;
};

}  // namespace bounce
