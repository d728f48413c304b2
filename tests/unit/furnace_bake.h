#pragma once
// A small dense bake of the furnace box (coloured albedo, no emission) with
// its Embree tracer, made once per test program: what the runtime's tests
// light again.
#include "bake/bake.h"
#include "raytrace/ray_tracer.h"
#include "test_scenes.h"

namespace bounce::test_scenes {

struct FurnaceBake {
  Scene scene = furnace_box(glm::vec3(0.7f, 0.5f, 0.3f), glm::vec3(0.0f));
  BakeResult bake;
  RayTracer tracer{scene};

  FurnaceBake() {
    BakeSettings s;
    s.voxel_resolution = 4;
    s.codec = CodecChoice::Dense;
    s.pictures = false;
    Diagnostics d;
    Progress progress;
    bake = Baker(scene, s, d).run(progress);
  }
};

inline const FurnaceBake& furnace_bake() {
  static const FurnaceBake f;
  return f;
}

}  // namespace bounce::test_scenes
