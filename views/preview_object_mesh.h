#pragma once
// A mesh file turned into the preview's moving object (preview_shapes.h):
// its triangles as corners within the unit ball, centred on the middle of
// its bounds, each corner with its face's normal (flat: the SH irradiance is
// smooth, and a loaded mesh need not carry normals).
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace bounce::views {

struct ObjectMesh {
  std::string name;  // the file's stem
  std::vector<glm::vec3> corners, normals;
};

// Reads `path` (OBJ, glTF, PLY, ... as scene meshes are read). Throws
// bounce::Error naming the file when it cannot be read or holds no triangle
// with an area.
ObjectMesh load_object_mesh(const std::string& path);

}  // namespace bounce::views
