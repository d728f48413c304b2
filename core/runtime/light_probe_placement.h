#pragma once
// Where a bake puts its light probes (runtime/light_probes.h): the centre of
// every empty cell of the bake's voxel grid that shares a face with an
// occupied one, i.e. the space within a voxel of the surfaces, where moving
// things walk, stand and pass, at the resolution the bake resolves light
// with. A candidate is rejected when it lies inside a closed solid (more
// than half of its test rays meet the back of a one-sided face: the inside
// of a block, of a closed wall) or sees no surface at all (every test ray
// leaves the scene or meets a back face). Probe volumes
// (runtime/probe_volume.h) add their lattices' points, tested alike.
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "raytrace/ray_tracer.h"
#include "runtime/probe_volume.h"
#include "voxel/voxelization.h"

namespace bounce {

// One probe volume's placement: its lattice's points, each kept or
// rejected by the same test as the probes next to the surfaces.
struct VolumePlacement {
  ProbeVolume volume;
  TransferGrid lattice;  // volume_lattice(volume)
  std::size_t candidates = 0;
  std::size_t rejected_enclosed = 0;
  std::size_t rejected_sees_nothing = 0;
  std::size_t placed = 0;
};

struct ProbePlacement {
  // The probes next to the surfaces in cell order (increasing linear
  // index), then each volume's in its lattice's cell order.
  std::vector<glm::vec3> position;
  // Next to the surfaces: whether they were placed, and why not when they
  // were asked for and skipped (too many for the limit, placement auto).
  bool surfaces = false;
  std::string surfaces_skipped;
  std::size_t candidates = 0;  // empty cells next to an occupied one
  std::size_t rejected_enclosed = 0;
  std::size_t rejected_sees_nothing = 0;
  std::vector<VolumePlacement> volumes;

  // The volumes' lattices with the range of `position` each one's probes fill.
  std::vector<ProbeLattice> lattices() const;
};

// What to place, and the limit on how many.
struct ProbePlacementRequest {
  bool surfaces = true;  // the probes next to the surfaces
  // Over the limit, the probes next to the surfaces are skipped (and said
  // why) rather than refused.
  bool surfaces_optional = false;
  std::vector<ProbeVolume> volumes;
  std::size_t max_probes = 0;
  const char* max_setting = "";      // named when there would be more
  const char* volumes_setting = "";  // named for a volume outside the scene or too dense
};

// Test rays per candidate, evenly over the sphere (a Fibonacci sphere).
inline constexpr int kProbeTestRays = 64;

// Places the probes. Throws bounce::Error before tracing or keeping
// anything: naming `volumes_setting` for a volume that does not meet the
// scene's bounds or whose lattice has more points than `max_probes`,
// naming `max_setting` when all the candidates together are more than
// `max_probes`. Thread-parallel; the result does not depend on the thread
// count.
ProbePlacement place_light_probes(const RayTracer& tracer, const Voxelization& voxels,
                                  const ProbePlacementRequest& request,
                                  Progress* progress = nullptr);

}  // namespace bounce
