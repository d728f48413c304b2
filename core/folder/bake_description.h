#pragma once
// What a bake folder's manifest says about the bake, typed: the scene it was
// made from, its grid, its content key and how many bounces its transport
// sums. Front ends read these fields, never the manifest's JSON, so a change
// of the manifest's layout is made in one place (docs/bake-format.md).
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "runtime/transfer_grid.h"
#include "scene/scene.h"

namespace bounce {

struct BakeDescription {
  std::string scene_name;
  // The scene file as the bake was given it (may have moved since).
  std::filesystem::path scene_path;
  std::size_t scene_triangles = 0;
  // The scene's lights at bake time, in scene order. Spot cone angles are not
  // stored: a spot light's angles are Light's defaults here.
  std::vector<Light> scene_lights;
  TransferGrid grid;
  // The content key of the bake's inputs (bake/bake_key.h); empty when the
  // bake was made without one.
  std::string key;
  // The most bounces any channel's series summed: a fixed K, or where the
  // series for K = infinity converged; 0 when neither is recorded.
  int bounces = 0;
};

// Reads the fields above from a manifest. Throws bounce::Error naming
// `manifest_path` when one is missing or of the wrong type.
BakeDescription describe_bake(const nlohmann::json& manifest,
                              const std::filesystem::path& manifest_path);

}  // namespace bounce
