#pragma once
// A lit triangle mesh as binary glTF 2.0 (.glb), the standard exchange format
// Blender, three.js, Babylon and every glTF viewer open without a plug-in:
//   POSITION, NORMAL     float VEC3 per vertex;
//   COLOR_0              float VEC3, the light tone-mapped to [0, 1] and kept
//                        linear (glTF vertex colours are linear; the viewer
//                        applies the display's transfer curve itself), with
//                        the same exposure as the PLY's colours (io/tone_map.h);
//   _RADIANCE            float VEC3, the exact linear light (an application
//                        attribute, ignored by viewers, read by scripts);
//   indices              unsigned int, counter-clockwise = front.
// The material is unlit (KHR_materials_unlit) with a white base colour, so a
// viewer shows the baked light itself instead of shading it again under its
// own lamps. Written through AtomicFile: a reader never sees half a file.
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

struct GlbMeshView {
  const std::vector<glm::vec3>& positions;
  const std::vector<glm::vec3>& normals;   // one per position, unit
  const std::vector<glm::vec3>& radiance;  // one per position, linear
  const std::vector<glm::uvec3>& triangles;
  std::string name = "lit";  // the node's and mesh's name in the viewer's outliner
};

// Returns the exposure the colours were tone-mapped with. Throws IoError
// (io/atomic_file.h) when the file cannot be written, bounce::Error when the
// arrays do not fit together, hold NaN/Inf, the mesh is empty or the file
// would exceed the format's 4 GiB.
float write_lit_glb(const std::filesystem::path& path, const GlbMeshView& mesh);

}  // namespace bounce
