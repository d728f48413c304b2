#pragma once
// The indirect light each patch would carry if the transport were exact: the
// path-traced reference's indirect radiosity (albedo x indirect irradiance)
// at every member sample of the patch, area-weighted over the patch. Passed
// through the same gather as a bake's own patch values, it gives the error
// of the patch layout alone (how finely and where the surface is cut into
// patches, and the gather from patches to pixels and vertices): what no
// accuracy of form factors, bounces or codec can take a row below. A row's
// error above it is the transport's.
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "patches/patch_set.h"
#include "patches/samples.h"
#include "reference/path_tracer.h"
#include "reference/reference_cache.h"

namespace bounce {

// One value per patch (R, G, B exitance, the units of T b); patches without
// area get 0. The reference at the samples is cached like the report's
// other reference points (by the points and the path tracer's settings).
struct ExactPatchLight {
  std::vector<glm::vec3> indirect;
  // The light leaving each patch after at least one reflection, direct
  // included (albedo x (direct + indirect irradiance)): what a final gather
  // (runtime/final_gather.h) sums.
  std::vector<glm::vec3> reflected;
  // Of each value, from the reference's variance at the samples (the
  // samples' estimates are independent): sum (a_s rho_s)^2 var_s / (sum a_s)^2.
  std::vector<glm::vec3> variance;
};
ExactPatchLight exact_patch_indirect(const ReferencePathTracer& pt, const SampleSet& samples,
                                     const PatchSet& patches, const ReferenceCache* cache,
                                     Progress* progress = nullptr);

}  // namespace bounce
