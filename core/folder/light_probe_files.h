#pragma once
// A bake's light probes (runtime/light_probes.h) as files of the bake folder
// (docs/bake-format.md, "Light probes"):
//   probe_position.npy       <f4 [probes, 3]   where each probe stands
//   probe_volume.npy         <f4 [volumes, 9]  with probe volumes: each one's
//                                              lattice (origin x y z, spacing,
//                                              cells x y z) and its probes
//                                              (first, count)
//   probe_gather_*.npy                         the gather of its 14 directions,
//                                              the vertices' gather files' layout,
//                                              probe p's direction k in row 14 p + k
#include <filesystem>
#include <optional>

#include "runtime/light_probes.h"

namespace bounce {

void write_light_probes(const std::filesystem::path& dir, const LightProbes& probes);

// nullopt when the folder has no probes; throws bounce::Error naming the file
// when they are there but inconsistent with each other, with `patches` or
// with `samples` (the bake's counts).
std::optional<LightProbes> read_light_probes(const std::filesystem::path& dir, std::size_t patches,
                                             std::size_t samples);

}  // namespace bounce
