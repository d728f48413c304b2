#pragma once
// One frame of the runtime on the patches: direct light from the current
// lights, the first hit b = albedo * E, the indirect light T b through
// whichever multiplier the caller chose (compressed OpenCL, compressed C++,
// dense), and what each patch finally sends out.
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "patches/patch_set.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_lights.h"
#include "scene/scene.h"

namespace bounce {

// indirect = T b, per patch and colour channel.
using IndirectMultiply =
    std::function<void(const std::vector<glm::vec3>& b, std::vector<glm::vec3>& indirect)>;
// The same into caller-owned memory (both n entries, not overlapping): what
// lets the runtime frame keep b and T b in its aliased arena
// (runtime/runtime_frame.h).
using IndirectMultiplySpan =
    std::function<void(std::span<const glm::vec3> b, std::span<glm::vec3> indirect)>;

struct PatchLighting {
  std::vector<glm::vec3> irradiance;  // direct, at each patch
  // Direct, at each sample (a patch's is their area-weighted mean): what a
  // final gather with sample sources reads.
  std::vector<glm::vec3> sample_irradiance;
  // b = albedo * irradiance (seen-weighted over the samples when the patches
  // have seen weights: runtime/seen_first_hit.h)
  std::vector<glm::vec3> first_hit;
  std::vector<glm::vec3> indirect;  // T b
  std::vector<glm::vec3> exitance;  // emission + b + T b: what the patch sends out
  double seconds_direct = 0.0, seconds_indirect = 0.0;
};

PatchLighting light_patches(const RayTracer& tracer, const SampleSet& samples,
                            const PatchSet& patches, const std::vector<Light>& lights,
                            const std::vector<AreaLight>& area, const IndirectMultiply& multiply);

}  // namespace bounce
