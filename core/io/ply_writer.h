#pragma once
// A lit triangle mesh as binary little-endian PLY, the format every mesh
// viewer (MeshLab, Blender, CloudCompare, ParaView) opens with vertex colours:
//   vertex: float x y z, float nx ny nz, uchar red green blue (tone-mapped:
//           io/tone_map.h, exposure in a header comment), float radiance_r
//           radiance_g radiance_b (linear, exact: what a script should read),
//           then any extra float properties (PlyScalar) in the order given;
//   face:   list uchar int vertex_indices (counter-clockwise = front).
// Written through AtomicFile: a reader never sees half a file.
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

struct PlyMeshView {
  const std::vector<glm::vec3>& positions;
  const std::vector<glm::vec3>& normals;   // one per position
  const std::vector<glm::vec3>& radiance;  // one per position, linear
  const std::vector<glm::uvec3>& triangles;
};

// One more float property per vertex, e.g. an error figure.
struct PlyScalar {
  std::string name;
  const std::vector<float>* values;  // one per position
};

// Returns the exposure the colours were tone-mapped with. Throws IoError
// (io/atomic_file.h) when the file cannot be written, bounce::Error when the
// arrays do not fit together.
float write_lit_ply(const std::filesystem::path& path, const PlyMeshView& mesh,
                    const std::vector<PlyScalar>& scalars = {});

}  // namespace bounce
