#pragma once
// The light on a bake's patches as a front end shows it, computed from the
// bake folder read back (LoadedBake): the patches' radiosity under the first
// evaluation light, and what the compressed matrix changes in the indirect
// light of a light set (the exact T.npy against the decoded T.dds), with one
// patch's row explained. The studio's patch view draws these; they are long
// enough on large bakes (a decode of n x n per channel, a product per
// colour) to be run away from a user interface's thread.
//
// A light set is what the bake's probe can light the patches with: set 0 is
// the scene's own lights together, as `bounce solve` lights the bake (the
// first hits of the scene's point, spot and directional lights, which are
// the first evaluation lights, and, with emissive triangles, of the area
// light, the last entry); set k >= 1 is evaluation light k - 1 alone.
#include <cstddef>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "compress/row_error_contributions.h"
#include "folder/bake_reader.h"
#include "metrics/patch_light_error.h"

namespace bounce {

// 1 + the evaluation lights: the light sets the bake can be lit with (0 when
// it holds no first hits).
std::size_t light_set_count(const LoadedBake& bake);

// b per patch (the light leaving each patch after the first hit) of light
// set `set`. Throws bounce::Error when the set is not one of the bake's.
std::vector<glm::vec3> light_set_first_hit(const LoadedBake& bake, std::size_t set);

struct PatchRadiosity {
  // Emission + b + T b per patch; the emission alone when `lit` is false.
  std::vector<glm::vec3> radiosity;
  // Whether the bake has the exact T.npy and a first evaluation light.
  bool lit = false;
};

// The light leaving each patch under the first evaluation light (the
// scene's first light), through the exact matrix.
PatchRadiosity patch_radiosity(const LoadedBake& bake);

// The bake's compressed matrix decoded, one n x n matrix per stored channel
// (row-major, patch order). Throws bounce::Error when the bake has none.
std::vector<std::vector<float>> decode_compressed(const LoadedBake& bake);

struct PatchIndirectError {
  PatchLightError error;  // T b against T~ b per patch, and the area-weighted figure
  // The picked patch's compressed row, its pieces ranked by their share of
  // the difference (when a patch was given).
  std::optional<RowErrorContributions> explanation;
};

// The indirect-light error the compressed matrix causes under light set
// `set`; `decoded` is decode_compressed(bake). Throws bounce::Error when the
// bake has no compressed matrix, no T.npy or no such set, or the patch is
// not one of the bake's.
PatchIndirectError compressed_indirect_error(const LoadedBake& bake,
                                             const std::vector<std::vector<float>>& decoded,
                                             std::size_t set,
                                             std::optional<std::size_t> patch = std::nullopt);

}  // namespace bounce
