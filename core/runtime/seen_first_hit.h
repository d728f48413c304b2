#pragma once
// A patch's first-hit light b as the scene's surfaces see it.
//
// b is the light a patch sends on after the first reflection, and T b the
// light it passes on through the later ones. Uniform over the patch, its
// area mean weighs every part alike; but within a patch the parts open to
// the sun are the parts other surfaces see (the top of a ledge, the face of a
// column toward the open court), and the shaded parts (a soffit, the back of
// the column) are seen little. On the sunlit Sponza the area mean fed T with
// too little of the light the other surfaces actually receive: the
// multi-bounce light at the camera's points was 7% low where b itself was
// right on average.
//
// With seen weights (PatchSet::member_seen_weight: each member sample's share
// of the rays a bake's final gather read through the patch, runtime/
// final_gather.h) a patch's b is the weighted mean of its samples' own
// albedo x E instead. A patch whose weights are all 0 (no gather ray read it)
// keeps albedo x its area-mean E.
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "patches/patch_set.h"
#include "runtime/final_gather.h"

namespace bounce {

// Sets `patches.member_seen_weight` from the seen weights of `gather`, the
// gather of the bake's lit-mesh vertices (cleared when it has none). Throws
// bounce::Error naming `what` when the gather was made for other patches or
// names a sample that is not a member of the patch.
void set_seen_weights(const FinalGather& gather, PatchSet& patches, const std::string& what);

// b per patch into `first_hit`: seen-weighted albedo_s x E_s over the
// members when the patch has seen weights (needs `sample_irradiance`, one
// per sample), else the patch's albedo x `irradiance`.
void seen_first_hit(const SampleSet& samples, const PatchSet& patches,
                    std::span<const glm::vec3> irradiance,
                    std::span<const glm::vec3> sample_irradiance, std::span<glm::vec3> first_hit);

}  // namespace bounce
