#pragma once
// The steps of Baker::run, declared once each, in one list per bake stage:
// the name of its timing entry in BakeResult::stages, when it applies, and
// what it does. A re-bake that does not run a stage takes its steps' results,
// their timing entries and the stage's diagnostics from the previous bake.
// Each step reports its own progress through the library functions it calls.
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "bake/bake.h"
#include "raytrace/ray_tracer.h"

namespace bounce {

// What the steps of one run share: its inputs, the result being built, and
// what lives only while the bake runs.
struct BakeRun {
  const Scene& scene;
  Diagnostics& diagnostics;
  BakeDistribution* distribution;  // null for a bake in one process
  Progress& progress;
  BakeResult& result;
  // Built with the geometry, or by the patch stage of a run that reuses the
  // geometry; the geometry, the patch and the form-factor stage trace rays
  // (a run of the form factors always runs the patches, see BakeStage).
  std::optional<RayTracer> tracer{};
  // Where F and each finished T go when the bake is out of core.
  std::optional<OutOfCorePolicy> out_of_core{};
  // Distributed bake: the root's executors, created as soon as the other
  // processes wait for them and destroyed (releasing them) however the run
  // ends: the transport's first (declared last), then the compression's.
  std::unique_ptr<CompressionExecutor> compressor{};
  std::unique_ptr<TransportExecutor> executor{};
  // Set by a process of a distributed bake that is not the root once it has
  // served the root's transport and compression: its run ends there.
  bool finished = false;
};

// Builds BakeRun::tracer; a step of the geometry stage and, when the
// geometry is reused, of the patch stage, under this timing name in both.
void build_tracer(BakeRun& run);
inline constexpr const char* kTracerTiming = "ray tracer (BVH build)";

struct BakeStep {
  const char* timing;               // its entry in BakeResult::stages; null: not timed
  bool (*applies)(const BakeRun&);  // null: whenever its stage runs
  void (*run)(BakeRun&);
};

// The steps of each stage, in the order they run.
std::span<const BakeStep> geometry_steps();
std::span<const BakeStep> patch_steps();
std::span<const BakeStep> form_factor_steps();
std::span<const BakeStep> transport_steps();
std::span<const BakeStep> compression_steps();

}  // namespace bounce
