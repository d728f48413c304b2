#pragma once
// Where a bake puts its light probes (runtime/light_probes.h): the centre of
// every empty cell of the bake's voxel grid that shares a face with an
// occupied one, i.e. the space within a voxel of the surfaces, where moving
// things walk, stand and pass, at the resolution the bake resolves light
// with. A candidate is rejected when it lies inside a closed solid (more
// than half of its test rays meet the back of a one-sided face: the inside
// of a block, of a closed wall) or sees no surface at all (every test ray
// leaves the scene or meets a back face).
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "raytrace/ray_tracer.h"
#include "voxel/voxelization.h"

namespace bounce {

struct ProbePlacement {
  std::vector<glm::vec3> position;  // in cell order (increasing linear index)
  std::size_t candidates = 0;       // empty cells next to an occupied one
  std::size_t rejected_enclosed = 0;
  std::size_t rejected_sees_nothing = 0;
};

// Test rays per candidate, evenly over the sphere (a Fibonacci sphere).
inline constexpr int kProbeTestRays = 64;

// Places the probes. Throws bounce::Error naming the setting
// `max_setting` before tracing or keeping anything when there are more than
// `max_probes` candidates. Thread-parallel; the result does not depend on
// the thread count.
ProbePlacement place_light_probes(const RayTracer& tracer, const Voxelization& voxels,
                                  std::size_t max_probes, const char* max_setting,
                                  Progress* progress = nullptr);

}  // namespace bounce
