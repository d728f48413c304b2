#pragma once
// Probe volumes: boxes where an artist wants light probes on a lattice of
// their own spacing, beside (or instead of) the ones placed next to the
// surfaces (runtime/light_probe_placement.h). A volume's probes stand at
// the centres of the cells of a grid of its own (its lattice), so the same
// trilinear blend with visibility lights a point inside it
// (runtime/probe_interpolation.h).
//
// As a setting (light_probe_volumes) a list of volumes is text:
//   "x0,y0,z0,x1,y1,z1,spacing"  one volume: its two corners and the
//                                distance between neighbouring probes,
//   volumes separated by ';'.
// scene.json's bake block writes the same as objects (docs/scene-format.md).
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "runtime/transfer_grid.h"

namespace bounce {

struct ProbeVolume {
  glm::vec3 lo{0.0f}, hi{0.0f};  // lo < hi on every axis
  float spacing = 1.0f;          // > 0
};

// A volume's probes: at the centres of `grid`'s cells, positions [first,
// first + count) of the bake's probes (fewer than the grid's cells: the
// placement rejects those inside solids or seeing nothing).
struct ProbeLattice {
  TransferGrid grid;
  std::size_t first = 0, count = 0;
};

// The volume's lattice: as many probes along each axis as the spacing fits
// in the box, plus one, centred in it (a box narrower than the spacing gets
// one probe across, at its middle).
TransferGrid volume_lattice(const ProbeVolume& volume);

// How many lattice points a volume has, in double: an absurd spacing gives
// a huge number rather than an overflow.
double volume_point_count(const ProbeVolume& volume);

// The volumes `text` lists (the format above; empty: none). Throws
// bounce::Error naming `setting` for malformed text, a number that is not
// finite, a box with lo >= hi on an axis or a spacing that is not positive.
std::vector<ProbeVolume> parse_probe_volumes(const std::string& text, const char* setting);

// The text that parse_probe_volumes reads back as `volumes` (shortest
// round-trip decimal of each float).
std::string probe_volumes_text(const std::vector<ProbeVolume>& volumes);

}  // namespace bounce
