#pragma once
// Which bake stages a change of settings makes stale. The pipeline is a
// chain (geometry -> patches -> form factors -> transport -> compression),
// so a change re-runs the earliest stage it affects and everything after it;
// the stages before are taken from the previous bake (Baker::run with a
// previous result). The studio re-bakes this way when a setting changes; see
// docs/studio.md.
#include <cstddef>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "settings/bake_settings.h"
#include "settings/bake_stage.h"

namespace bounce {

// How many stages a bake has (None is not one).
inline constexpr std::size_t kBakeStageCount = static_cast<std::size_t>(BakeStage::None);

const char* to_string(BakeStage stage);

struct RebakePlan {
  BakeStage first = BakeStage::Geometry;  // this stage and every later one run
  // One line per changed setting that matters, e.g. "bounces: auto -> 4".
  std::vector<std::string> reasons;

  bool runs(BakeStage stage) const {
    return static_cast<int>(stage) >= static_cast<int>(first) && stage != BakeStage::None;
  }
};

// `previous`: the settings of an earlier bake of the same scene as it resolved
// them (BakeResult::settings); `next`: the settings asked for now, as a user
// gives them (scene defaults not yet applied). Settings that only change what
// the writer writes (dump_matrices, pictures) re-run nothing.
RebakePlan plan_rebake(const Scene& scene, const BakeSettings& previous, const BakeSettings& next);

// Each mesh's patch density (MeshInfo::patch_density), in mesh order: what
// a bake's patches are made with (BakeResult::patch_density).
std::vector<float> patch_densities(const Scene& scene);

// The plan Baker::run follows: the settings' plan above, and the scene
// itself taken to be the previous bake's except for its meshes' patch
// densities (`previous_densities`, the previous bake's), which a scene.json
// edit or the studio's mesh list may change without touching the geometry.
// A changed density re-runs from the patches (the voxels and samples do not
// depend on it), one reason per mesh ("patch density of 'floor': 1 -> 4").
RebakePlan plan_rebake(const Scene& scene, const BakeSettings& previous,
                       const std::vector<float>& previous_densities, const BakeSettings& next);

}  // namespace bounce
