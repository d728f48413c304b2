#pragma once
// Closure of each patch: the share of the light leaving the surface it stands
// for that lands on surface some patch stands for. It is what the patch's
// form-factor row must sum to: 1 in a closed room, less where light escapes
// to the sky, strikes the back of a one-sided surface or strikes surface no
// sample carries (none of which any patch can receive).
//
// Measured with rays: each patch's rays start on the polygons its member
// samples carry (spread over them by area) and leave with cosine-distributed
// directions, the distribution of diffusely emitted light, so the share of
// rays that hit is the share of the energy that does. Directions come from a
// stratified pattern (raytrace/cosine_lattice.h), so the estimate's noise falls faster than
// 1/sqrt(rays). A ray counts as closed when its first hit is the front of a triangle (or either
// side of a two-sided one) that a patch stands for (`lookup`). In a closed scene every ray hits
// such a surface, so the closure is exactly 1 by construction, not by luck of the estimate.
#include <cstdint>
#include <vector>

#include "base/progress.h"
#include "patches/patch_set.h"
#include "patches/samples.h"
#include "patches/surface_patch_lookup.h"
#include "raytrace/ray_tracer.h"
#include "voxel/voxelization.h"

namespace bounce {

struct ClosureSettings {
  int rays_per_patch = 512;
  std::uint64_t seed = 1;
};

struct PatchClosure {
  std::vector<float> closure;  // per patch, in [0, 1]
  int rays_per_patch = 0;
  // Summary: area-weighted mean, extremes, and how many patches are open
  // (closure below 1) at all.
  double mean = 0.0;
  double min = 1.0;
  double max = 0.0;
  std::size_t open_patches = 0;
  // Largest standard error of one patch's closure, sqrt(c (1 - c) / rays):
  // an upper bound, since stratification only lowers it.
  double standard_error_max = 0.0;
};

PatchClosure measure_closure(const Scene& scene, const RayTracer& tracer, const Voxelization& vox,
                             const SampleSet& samples, const PatchSet& patches,
                             const SurfacePatchLookup& lookup, const ClosureSettings& settings,
                             Progress* progress = nullptr);

}  // namespace bounce
