#pragma once
// Light probes' irradiance at any point of the empty space: a blend of the
// probes around it that can see it. Probes sit at the centres of voxel cells
// of the bake's grid (runtime/light_probe_placement.h), so the 2 x 2 x 2
// cells whose centres surround a point hold its candidates, weighted
// trilinearly. A wall thinner than a voxel leaves probes on both of its
// sides within one such block, so a blend of the weights alone carries the
// lit side's light through the wall: each candidate whose segment to the
// point meets a surface is dropped and the others' weights renormalised.
// When none is left (a point within half a voxel of a surface, whose block
// reaches into the surface's occupied cells; a point in a wall's cell, the
// block's probes all behind the wall), the probes of the 3 x 3 x 3 cells
// around the point's own that see it are blended with a tent twice as
// wide, so that an object moving along a floor still blends its
// neighbours; when none of those sees it either, the nearest probe within
// two cells that does stands in, and failing that the blend is empty.
//
// Probes of a probe volume (runtime/probe_volume.h) stand on the volume's
// own lattice: a point inside a volume's lattice blends that lattice's
// probes trilinearly with the same visibility test, the first volume that
// has a probe seeing it; a point no volume lights falls back to the probes
// next to the surfaces as above. Beyond the volume's outer probes (the
// outer half cell of its lattice) the volume's share falls linearly to
// zero and the probes next to the surfaces take the rest, so that an
// object leaving a volume does not jump from one lattice's light to the
// other's.
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/ray_tracer.h"
#include "runtime/light_probes.h"
#include "runtime/probe_volume.h"
#include "runtime/transfer_grid.h"

namespace bounce {

// Which probes light a point, and how much each.
struct ProbeBlend {
  // How the probes were found: the trilinear block, the wider tent over
  // the 3 x 3 x 3 cells around the point's own, the nearest in reach, or
  // none (no probe within two cells sees the point).
  enum class Stage : std::uint8_t { kTrilinear, kNeighbourhood, kNearest, kNone };
  // A volume's 8 and, where it fades out, the 27 of the cells around.
  static constexpr std::size_t kMaxProbes = 8 + 27;
  std::array<std::uint32_t, kMaxProbes> probe{};
  std::array<float, kMaxProbes> weight{};  // sum to 1 when count > 0
  std::size_t count = 0;
  Stage stage = Stage::kNone;
  int rays = 0;  // occlusion rays traced
};

// Whether a candidate probe must see the point. kIgnored is the blend that
// leaks through thin walls, kept to measure what the test prevents.
enum class ProbeVisibility : std::uint8_t { kTested, kIgnored };

class ProbeInterpolator {
 public:
  // `positions`: the probes; those of `volumes` at the centres of their
  // lattices' cells, every other one at the centre of a cell of `grid`.
  // Throws bounce::Error naming the probe when one is not at a cell centre
  // or two share a cell, and when a volume's probes are not among
  // `positions`. The tracer must outlive the interpolator.
  ProbeInterpolator(const std::vector<glm::vec3>& positions, const TransferGrid& grid,
                    const RayTracer& tracer, const std::vector<ProbeLattice>& volumes = {});

  ProbeBlend blend(const glm::vec3& point,
                   ProbeVisibility visibility = ProbeVisibility::kTested) const;

  // The irradiance SH at `point`: the blend of the probes' `sh`
  // (kShCoefficients per probe, the convention of runtime/light_probes.h).
  // Returns the blend; its count is 0 and `out` zero when no probe sees
  // the point.
  ProbeBlend sh_at(const glm::vec3& point, const std::vector<glm::vec3>& sh,
                   std::array<glm::vec3, kShCoefficients>& out,
                   ProbeVisibility visibility = ProbeVisibility::kTested) const;

  std::size_t size() const { return positions_.size(); }

 private:
  // Probes at the centres of a grid's cells: (linear cell index, probe),
  // sorted by cell.
  struct Lattice {
    TransferGrid grid;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> cells;
    // The probe in cell `c`, or -1 (also for cells outside the grid).
    std::int64_t probe_in(const glm::ivec3& c) const;
    // The share of the blend this lattice takes at `point`: 1 up to its
    // outer probes, falling linearly to 0 at the edge of its cells.
    float share_at(const glm::vec3& point) const;
  };
  void add_probe(Lattice& lattice, std::uint32_t probe) const;
  static void check_distinct(Lattice& lattice);
  bool sees(const glm::vec3& point, std::uint32_t probe) const;
  // Adds the probe if it has a weight and (when tested) sees the point.
  void consider(const glm::vec3& point, std::uint32_t probe, float weight,
                ProbeVisibility visibility, ProbeBlend& out) const;
  void trilinear(const Lattice& lattice, const glm::vec3& point, ProbeVisibility visibility,
                 ProbeBlend& out) const;
  void neighbourhood(const glm::vec3& point, ProbeVisibility visibility, ProbeBlend& out) const;
  void nearest_in_reach(const glm::vec3& point, ProbeVisibility visibility, ProbeBlend& out) const;
  // The probes next to the surfaces: trilinear, then the wider tent, then
  // the nearest in reach.
  void surfaces_blend(const glm::vec3& point, ProbeVisibility visibility, ProbeBlend& out) const;
  void fade_to_surfaces(const glm::vec3& point, ProbeVisibility visibility, float share,
                        ProbeBlend& out) const;

  std::vector<glm::vec3> positions_;
  const RayTracer& tracer_;
  Lattice surfaces_;              // the probes next to the surfaces, on the bake's grid
  std::vector<Lattice> volumes_;  // each volume's, in the order given
};

}  // namespace bounce
