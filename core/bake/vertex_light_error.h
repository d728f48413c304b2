#pragma once
// What the compressed matrix changes in the indirect light the lit mesh's
// vertices receive, as the bake measures it per patch (errors.indirect_light)
// but after the transfer: each vertex's stored final gather summed over the
// patches' indirect light T b (and, where the gather reads samples, each
// sample's share of its patch's T b; the samples' own first-hit light is the
// same for both matrices and left out, as b is left out of the patch figure).
//
// Per evaluation light, the relative RMS over vertices and colours,
//   sqrt(sum_v |E~_v - E_v|^2 / sum_v |E_v|^2),
// every vertex weighing the same; mean and max over the lights that put any
// indirect light on a vertex.
#include <vector>

#include "compress/codec.h"
#include "compress/compression_error.h"
#include "patches/patch_set.h"
#include "patches/samples.h"
#include "runtime/final_gather.h"

namespace bounce {

// `exact`: the stored channels of the exact matrix (n x n, patch order);
// `compressed`: the same matrix compressed; `probe`: the evaluation lights.
// Throws bounce::Error when the gather, samples, patches and matrices do not
// fit together.
IndirectLightError vertex_light_error(const FinalGather& gather, const SampleSet& samples,
                                      const PatchSet& patches,
                                      const std::vector<const float*>& exact,
                                      const CompressedMatrix& compressed,
                                      const IndirectLightProbe& probe);

}  // namespace bounce
