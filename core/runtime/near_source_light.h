#pragma once
// The light of the final gather's near sources each frame: one shadow ray per
// light and source (fewer under a shadow budget), the area lights' strata,
// and the patch's indirect light, per source (see NearSources in
// runtime/final_gather.h).
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/ray_tracer.h"
#include "runtime/area_light_cache.h"
#include "runtime/area_lights.h"
#include "runtime/final_gather.h"
#include "runtime/shadow_budget.h"
#include "scene/scene.h"

namespace bounce {

// Writes the light of near source i to out[i * stride], three floats (and a
// zero fourth when stride is 4, the product's padded light). `tracer` null:
// no direct light, the patches' indirect light only. `area_cache` keeps the
// area lights' part between calls; `budget` spreads the shadow rays over
// frames. Throws bounce::Error when a source names a patch that is not there.
void light_near_sources(const NearSources& near, const RayTracer* tracer,
                        const std::vector<Light>& lights, const std::vector<AreaLight>& area,
                        const std::vector<glm::vec3>& patch_indirect, float* out,
                        std::size_t stride, AreaLightCache* area_cache = nullptr,
                        ShadowBudget* budget = nullptr);

}  // namespace bounce
