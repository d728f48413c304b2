#pragma once
// One light move, step by step, per light of a baked scene: the light is
// moved along a short path frame after frame (a point or spot light around a
// circle, a sun turned about the up axis), and each frame's direct light,
// T b, gather product and near sources are timed, for every shadow ray
// traced in the frame a light moves and for the rays spread over k frames
// (runtime/shadow_budget.h). With the spread rays, each frame's irradiance
// at the lit mesh's vertices is compared with the frame that traced them
// all, while the light moves and after it stops, until it is exact. Both
// sessions multiply T b with the float32 loop: a loop each chose by timing
// could differ (bfloat16 rounds), and the difference would not be the rays'.
#include <filesystem>
#include <string>
#include <vector>

namespace bounce {

struct LightMoveSettings {
  std::filesystem::path scene;  // empty: the manifest's
  int moves = 16;               // frames the light moves for
  int shadow_frames = 8;        // k of the spread rays
};

// Milliseconds per step, median over the moving frames. `probes`: the light
// probes' SH from the same frame (their gather product and SH fit; 0 for a
// bake without probes), part of `whole`.
struct LightMoveSteps {
  double direct = 0.0, indirect = 0.0, product = 0.0, near = 0.0, whole = 0.0, probes = 0.0;
};

struct LightMoveRow {
  std::string light, type;   // the light's name and kind ("area" for the emitters)
  LightMoveSteps every_ray;  // every ray in the frame the light moved
  LightMoveSteps spread;     // rays spread over shadow_frames
  // Relative RMS difference of the vertices' irradiance, spread against
  // every ray, per frame: `moves` moving frames, then frames with the
  // light still until the difference is 0 (at most shadow_frames + 1).
  std::vector<double> difference;
  int frames_to_exact = -1;  // frames after the light stopped; -1: never
};

struct LightMoveBench {
  std::string scene;
  std::size_t patches = 0, vertices = 0, near_sources = 0, probes = 0;
  int shadow_frames = 0;
  std::vector<LightMoveRow> rows;
};

// Throws bounce::Error for a bake without a final gather or settings out
// of range (moves 1..1000, shadow_frames 1..64).
LightMoveBench run_light_move_bench(const std::filesystem::path& bake,
                                    const LightMoveSettings& settings);

}  // namespace bounce
