#pragma once
// The stages of a bake, in the order the pipeline runs them: what a setting's
// row (settings/settings_table.h) says a change of it re-runs, and what a
// re-bake plan (bake/rebake_plan.h) starts from.

namespace bounce {

// In pipeline order. Geometry: voxel grid, ray tracer, samples and their
// albedo from textures and vertex colours. Patches: the patches, clustered
// from those samples (what a mesh's patch density changes). FormFactors: form
// factors, their checks (pruning) and the evaluation lights' first-hit light
// (it needs the patches only). Transport: the multi-bounce matrices.
// Compress: how they are stored. None: nothing to run.
// A plan never starts at FormFactors: the checks prune patches that see
// nothing, so new form factors need the unpruned patches: settings of the
// form-factor stage re-run from Patches.
enum class BakeStage {
  Geometry = 0,
  Patches = 1,
  FormFactors = 2,
  Transport = 3,
  Compress = 4,
  None = 5
};

}  // namespace bounce
