// What a re-bake after one mesh's patch density changed costs against a full
// bake, in one process, as the studio's mesh list runs it: the Cornell box at
// a small grid (BOUNCE_REBAKE_VOXEL sets another: 16 is the scene's own, a
// 2-3 minute bake), both times and each step's printed as "[ measured ]".
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bake/bake.h"
#include "scene/scene_loader.h"

namespace bounce {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void print_steps(const char* what, const BakeResult& r) {
  std::printf("[ measured ] %s:", what);
  for (const StageStats& s : r.stages) std::printf(" %s %.2f s;", s.name.c_str(), s.seconds);
  std::printf("\n");
}

TEST(RebakeTiming, OneMeshDensityAgainstAFullBake) {
  Diagnostics d;
  const Scene scene = SceneLoader(d).load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-box");
  BakeSettings s;
  const char* voxel = std::getenv("BOUNCE_REBAKE_VOXEL");
  s.voxel_resolution = voxel ? std::atoi(voxel) : 4;
  s.transport.backend = TransportSettings::Backend::OpenBLAS;
  s.pictures = false;
  Progress quiet;

  auto start = std::chrono::steady_clock::now();
  const BakeResult full = Baker(scene, s, d).run(quiet);
  const double full_s = seconds_since(start);

  Scene edited = scene;
  edited.meshes.front().patch_density = 2.0f;
  start = std::chrono::steady_clock::now();
  const BakeResult again = Baker(edited, s, d).run(quiet, &full);
  const double again_s = seconds_since(start);

  EXPECT_EQ(again.plan.first, BakeStage::Patches);
  std::printf(
      "[ measured ] Cornell box --voxel %d: full bake %.2f s (%zu patches), re-bake after "
      "'%s' density 1 -> 2: %.2f s (%zu patches), %.0f%% of the full bake\n",
      *s.voxel_resolution, full_s, full.patches.size(), edited.meshes.front().name.c_str(), again_s,
      again.patches.size(), 100.0 * again_s / full_s);
  print_steps("full", full);
  print_steps("re-bake", again);
  // Not a speed target (the machine's load varies): the re-bake must not
  // cost more than a full bake and then some.
  EXPECT_LT(again_s, 1.5 * full_s + 1.0);
}

}  // namespace
}  // namespace bounce
