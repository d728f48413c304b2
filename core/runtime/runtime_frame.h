#pragma once
// The runtime's per-frame work on the patches run through the frame graph
// (dynamic/frame_graph.h, issue 8 section 3: "the runtime solve runs through
// this graph"). The graph is built and compiled once per bake and multiply
// path, so its transient arena is allocated once; solve() then executes it
// once per light configuration without allocating:
//
//   direct light      lights            -> E        E = direct irradiance
//   first hit         E                 -> b        b = albedo * E
//   record direct     E, b              -> record   (optional) E, b per patch
//   indirect product  T, b              -> T b      the caller's multiply
//   apply             b, T b            -> exitance emission + b + T b
//   record indirect   T b               -> record   (optional) T b per patch
//
// E lives only in the graph's arena (transient). b and T b are persistent
// vectors owned by the frame and imported into the graph, because the
// multiply paths (IndirectMultiply: compressed C++, OpenCL, dense) take and
// fill std::vector; they are sized once here, and the multipliers resize
// their output only when its size differs, so no frame allocates. The
// results equal light_patches() (runtime/patch_lighting.h): the same
// irradiance per sample (irradiance_at with the sample's index as seed), the
// same sums in the same order.
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "dynamic/frame_graph.h"
#include "patches/patch_set.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_lights.h"
#include "runtime/patch_lighting.h"
#include "scene/scene.h"

namespace bounce {

struct RuntimeFrameSettings {
  // Transients share memory where their lifetimes do not overlap.
  bool alias = true;
  // Keep E, b and T b per patch in record() (n x 3 x 3 floats, the layout of
  // `bounce solve`'s patch_light.npy); off: only b, T b and the exitance.
  bool record = true;
  int area_strata = 4;  // as direct_irradiance()
};

class RuntimeFrame {
 public:
  // Builds and compiles the graph. The tracer, samples, patches and multiply
  // must outlive the frame. Throws bounce::Error when the patches have no
  // samples table to match.
  RuntimeFrame(const RayTracer& tracer, const SampleSet& samples, const PatchSet& patches,
               IndirectMultiply multiply, RuntimeFrameSettings settings = {});
  // The passes capture `this`.
  RuntimeFrame(const RuntimeFrame&) = delete;
  RuntimeFrame& operator=(const RuntimeFrame&) = delete;

  // One frame: runs every pass for these lights. The results below hold
  // until the next solve().
  void solve(const std::vector<Light>& lights, const std::vector<AreaLight>& area = {});

  std::size_t size() const { return n_; }
  const std::vector<glm::vec3>& first_hit() const { return first_hit_; }
  const std::vector<glm::vec3>& indirect() const { return indirect_; }
  const std::vector<glm::vec3>& exitance() const { return exitance_; }
  // Per patch: E (r, g, b), b, T b; empty unless settings.record.
  const std::vector<float>& record() const { return record_; }

  // Seconds each pass took in the last solve(), in pass order.
  const std::vector<double>& pass_seconds() const { return pass_seconds_; }
  const FrameGraph& graph() const { return graph_; }
  // The arena (with the settings' aliasing), what the transients would take
  // each in its own range, and the imported (persistent) per-patch buffers.
  std::size_t transient_bytes() const { return graph_.transient_bytes(); }
  std::size_t unaliased_transient_bytes() const { return graph_.unaliased_transient_bytes(); }
  std::size_t imported_bytes() const { return graph_.imported_bytes(); }

 private:
  void add_timed_pass(std::string name, std::vector<FrameGraph::ResourceId> reads,
                      std::vector<FrameGraph::ResourceId> writes, FrameGraph::PassFunction run);

  const RayTracer& tracer_;
  const SampleSet& samples_;
  const PatchSet& patches_;
  IndirectMultiply multiply_;
  RuntimeFrameSettings settings_;
  std::size_t n_ = 0;
  // The current frame's lights, set by solve() for the direct-light pass.
  const std::vector<Light>* lights_ = nullptr;
  const std::vector<AreaLight>* area_ = nullptr;
  std::vector<glm::vec3> first_hit_, indirect_, exitance_;
  std::vector<float> record_;
  std::vector<double> pass_seconds_;
  FrameGraph graph_;
};

}  // namespace bounce
