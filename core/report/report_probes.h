#pragma once
// The light probes' column of `bounce report`: each row's probes against the
// path tracer at the same points for every row. The points are a probe
// placement of their own (runtime/light_probe_placement.h) on the report's
// evaluation grid, at most kReportProbePoints of them, each with the six
// axis normals; the reference's indirect irradiance there is estimated once
// (and cached with the report's other references). A row's irradiance at a
// point is its probes' SH blended there (runtime/probe_interpolation.h,
// visibility tested), so the column measures what a moving object would get
// anywhere in the empty space, not only at the row's own probe positions:
// the probes' gather, their SH fit and the blend between them.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "bake/bake.h"
#include "base/progress.h"
#include "raytrace/ray_tracer.h"
#include "reference/path_tracer.h"
#include "reference/probe_reference_error.h"

namespace bounce {

class ReferenceCache;

inline constexpr std::size_t kReportProbePoints = 64;

class ReportProbes {
 public:
  // Places the evaluation points on a grid of `eval_grid` cells and estimates
  // the reference there (from `cache` when it holds them).
  ReportProbes(const RayTracer& tracer, const ReferencePathTracer& reference, int eval_grid,
               const ReferenceCache* cache, Progress* progress);

  std::size_t points() const { return positions_.size(); }

  // The row baked as `bake` (with light probes), lit with `reflected` (b +
  // T b per patch) and `sample_light` (sample_exitance of the frame). A bake
  // without probes gives every point zero.
  ProbeReferenceError measure(const BakeResult& bake, const std::vector<glm::vec3>& reflected,
                              const std::vector<glm::vec3>& sample_light) const;

 private:
  const RayTracer& tracer_;
  std::vector<glm::vec3> positions_;
  std::vector<ReferencePoint> points_;
  PointReference reference_;
};

}  // namespace bounce
