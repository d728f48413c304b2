#pragma once
// What the live preview uploads of a lit mesh: one vertex per triangle
// corner, because albedo, emission and texture coordinates belong to the
// scene triangle and neighbours of another material share mesh vertices.
// Corners are grouped by material, so that each material is one draw with
// its own textures bound.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bounce/relight.h"
#include "bounce/scene.h"

namespace bounce::views {

struct PreviewCorners {
  // Per corner: position, normal, albedo, emission (3 floats each), texture
  // coordinates (2), whether they are known (1), tangent and handedness (4).
  static constexpr int kFloats = 19;
  std::vector<float> floats;
  std::vector<std::uint32_t> vertex;  // the mesh vertex of each corner
  // Corners first .. first + count - 1 have material `material`.
  struct MaterialRange {
    std::size_t first = 0, count = 0, material = 0;
  };
  std::vector<MaterialRange> materials;
};

PreviewCorners preview_corners(const Scene& scene, const LitMesh& mesh);

}  // namespace bounce::views
