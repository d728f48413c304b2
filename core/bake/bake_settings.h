#pragma once
// Every knob of a bake, with the defaults a user gets when they say nothing.
#include <cstdint>
#include <optional>
#include <string>

#include "base/error.h"
#include "scene/scene.h"

namespace bounce {

enum class PatchMode { Virtual, Voxel };

struct BakeSettings {
  class InvalidSetting : public Error {
   public:
    using Error::Error;
  };

  // Exactly one of these two decides the grid; with neither, the scene's
  // defaults apply, then `kDefaultVoxelResolution`.
  std::optional<int> voxel_resolution;
  std::optional<int> patches_total;
  // Unset: the scene's bake block, else the default below.
  std::optional<int> patches_per_voxel;
  PatchMode patch_mode = PatchMode::Virtual;
  std::optional<int> samples_per_face;
  int visibility_rays = 8;   // rays per patch pair
  std::uint64_t seed = 1;
  bool dump_matrices = false;

  static constexpr int kDefaultVoxelResolution = 16;
  // 3: a voxel at a box corner holds three orientations, and clustering merges
  // by normal first, so three patches keep every corner's faces apart; on a
  // flat wall the three subdivide the surface instead.
  static constexpr int kDefaultPatchesPerVoxel = 3;
  static constexpr int kDefaultSamplesPerFace = 4;  // 4x4 rays per voxel face: 96 per voxel

  // Fills unset values from the scene's bake block, then the defaults, so
  // every optional above except the grid choice has a value afterwards.
  void apply_scene_defaults(const BakeDefaults& defaults);
  // Throws InvalidSetting naming the option for absurd values.
  void validate() const;
};

std::string to_string(PatchMode mode);

}  // namespace bounce
