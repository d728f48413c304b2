#pragma once
// A regular grid of cubic cells over the scene's bounds, padded slightly so
// that surfaces lying exactly on the bounds (the walls of a closed room) fall
// inside the outer layer of cells instead of on their faces.
#include <cstdint>

#include <glm/glm.hpp>

#include "base/error.h"
#include "scene/scene.h"

namespace bounce {

class VoxelGrid {
 public:
  class SettingsError : public Error {
   public:
    using Error::Error;
  };

  static constexpr int kMaxResolution = 4096;

  VoxelGrid() = default;
  // `resolution` = number of cells along the longest axis of the bounds.
  VoxelGrid(const Bounds& scene_bounds, int resolution);
  // The grid a bake recorded (its minimum corner, cell size and cell counts),
  // the same cells to the bit. Throws SettingsError for a non-positive or
  // non-finite cell size, or counts outside [1, kMaxResolution].
  static VoxelGrid restore(const glm::vec3& origin, float cell_size, const glm::ivec3& dims);

  const Bounds& bounds() const { return bounds_; }
  glm::ivec3 dims() const { return dims_; }
  float cell_size() const { return cell_; }
  int resolution() const { return resolution_; }
  std::uint64_t cell_count() const {
    return static_cast<std::uint64_t>(dims_.x) * static_cast<std::uint64_t>(dims_.y) *
           static_cast<std::uint64_t>(dims_.z);
  }

  std::uint64_t linear_index(const glm::ivec3& c) const {
    return (static_cast<std::uint64_t>(c.z) * static_cast<std::uint64_t>(dims_.y) +
            static_cast<std::uint64_t>(c.y)) *
               static_cast<std::uint64_t>(dims_.x) +
           static_cast<std::uint64_t>(c.x);
  }
  glm::ivec3 coord_of(std::uint64_t linear) const;
  // Cell containing p (clamped into the grid).
  glm::ivec3 cell_of(const glm::vec3& p) const;
  Bounds cell_bounds(const glm::ivec3& c) const;
  // Lower coordinate of the cell plane `i` along `axis` (i in [0, dims[axis]]).
  float plane(int axis, int i) const { return bounds_.lo[axis] + static_cast<float>(i) * cell_; }

 private:
  Bounds bounds_;
  glm::ivec3 dims_{1};
  float cell_ = 1.0f;
  int resolution_ = 1;
};

}  // namespace bounce
