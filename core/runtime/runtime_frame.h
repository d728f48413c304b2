#pragma once
// The runtime's per-frame work on the patches run through the frame graph
// (runtime/frame_graph.h: the runtime solve runs through this graph, so its
// transient buffers can share memory). The graph is built and compiled once per bake and multiply
// path, so its transient arena is allocated once; solve() then executes it
// once per light configuration without allocating:
//
//   direct light      lights            -> E        E = direct irradiance
//   first hit         E                 -> b        b = albedo * E (seen-
//                                                    weighted over the samples
//                                                    with seen weights:
//                                                    runtime/seen_first_hit.h)
//   record direct     E, b              -> record   (optional) E, b per patch
//   indirect product  T, b              -> T b      the caller's multiply
//   apply             b, T b            -> exitance emission + b + T b
//   record indirect   T b               -> record   (optional) T b per patch
//   publish           b, T b            -> first_hit(), indirect() (optional)
//
// E, b and T b are transients: they live in the graph's one arena at the
// offsets of the aliasing allocator, so E (dead after "record direct") and
// T b (born in "indirect product") share one range, and the arena holds two
// per-patch colour buffers instead of three. The multiply writes T b
// straight into the arena (IndirectMultiplySpan); a multiply that takes
// std::vector (IndirectMultiply) still works, through two scratch vectors
// (one copy of b and T b per frame). The exitance and the record are the
// frame's persistent outputs; first_hit() and indirect() are copies of b
// and T b made by the last pass (settings.publish), which a caller that
// reads the record instead can turn off. Nothing is allocated per frame.
// The results equal light_patches() (runtime/patch_lighting.h): the same
// direct_irradiance() per patch, the same sums in the same order.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "patches/patch_set.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_light_cache.h"
#include "runtime/area_lights.h"
#include "runtime/carried_polygon_frames.h"
#include "runtime/frame_graph.h"
#include "runtime/patch_lighting.h"
#include "runtime/shadow_budget.h"
#include "scene/scene.h"

namespace bounce {

struct RuntimeFrameSettings {
  // Transients share memory where their lifetimes do not overlap.
  bool alias = true;
  // Keep E, b and T b per patch in record() (n x 3 x 3 floats, the layout of
  // `bounce solve`'s patch_light.npy); off: only b, T b and the exitance.
  bool record = true;
  int area_strata = kAreaStrata;  // as direct_irradiance()
  // Copy b and T b out of the arena for first_hit() and indirect() (two
  // persistent per-patch buffers); off: those stay empty, and b and T b are
  // in record() (when settings.record) and exitance().
  bool publish = true;
  // Keep each sample's direct irradiance (sample_irradiance()), for a final
  // gather with sample sources.
  bool sample_irradiance = false;
  // The samples' shadow rays to a light that moved, spread over this many
  // frames (runtime/shadow_budget.h): 1, every ray in the frame it moved.
  int shadow_frames = 1;
  // FrameGraph::set_poison_dead_transients: NaN into every dead transient's
  // range after each pass (tests: proves no pass reads a dead or overwritten
  // buffer).
  bool poison_dead_transients = false;
};

class RuntimeFrame {
 public:
  // Builds and compiles the graph. The tracer, samples, patches and multiply
  // must outlive the frame. Throws bounce::Error when the patches have no
  // samples table to match.
  RuntimeFrame(const RayTracer& tracer, const SampleSet& samples, const PatchSet& patches,
               IndirectMultiply multiply, RuntimeFrameSettings settings = {});
  // The same with a multiply that writes into the arena (no copies). Pass an
  // IndirectMultiplySpan object: a lambda taking spans also converts to
  // IndirectMultiply (vectors convert to spans), so it would be ambiguous.
  RuntimeFrame(const RayTracer& tracer, const SampleSet& samples, const PatchSet& patches,
               IndirectMultiplySpan multiply, RuntimeFrameSettings settings = {});
  // The passes capture `this`.
  RuntimeFrame(const RuntimeFrame&) = delete;
  RuntimeFrame& operator=(const RuntimeFrame&) = delete;

  // One frame: runs every pass for these lights. The results below hold
  // until the next solve().
  void solve(const std::vector<Light>& lights, const std::vector<AreaLight>& area = {});

  std::size_t size() const { return n_; }
  // Empty unless settings.publish.
  const std::vector<glm::vec3>& first_hit() const { return first_hit_; }
  const std::vector<glm::vec3>& indirect() const { return indirect_; }
  const std::vector<glm::vec3>& exitance() const { return exitance_; }
  // Empty unless settings.sample_irradiance.
  const std::vector<glm::vec3>& sample_irradiance() const { return sample_irradiance_; }
  // Per patch: E (r, g, b), b, T b; empty unless settings.record.
  const std::vector<float>& record() const { return record_; }
  // The samples' shadows are exact for the last frame's lights (always, with
  // shadow_frames 1).
  bool shadows_settled() const { return !shadows_ || shadows_->settled(); }
  // Batches of samples (one per patch) whose shadow rays the last frame
  // traced, over all lights; with shadow_frames 1, every patch per light.
  std::size_t traced_shadow_batches() const;

  // Seconds each pass took in the last solve(), in pass order.
  const std::vector<double>& pass_seconds() const { return pass_seconds_; }
  const FrameGraph& graph() const { return graph_; }
  // The arena (with the settings' aliasing), what the transients would take
  // each in its own range, and the imported (persistent) per-patch buffers:
  // exitance, record, and the published b and T b.
  std::size_t transient_bytes() const { return graph_.transient_bytes(); }
  std::size_t unaliased_transient_bytes() const { return graph_.unaliased_transient_bytes(); }
  std::size_t imported_bytes() const { return graph_.imported_bytes(); }

 private:
  void build();
  void add_timed_pass(std::string name, std::vector<FrameGraph::ResourceId> reads,
                      std::vector<FrameGraph::ResourceId> writes, FrameGraph::PassFunction run);

  const RayTracer& tracer_;
  const SampleSet& samples_;
  const PatchSet& patches_;
  IndirectMultiplySpan multiply_;
  RuntimeFrameSettings settings_;
  std::size_t n_ = 0;
  // The samples' polygon frames, computed once: they depend on the geometry
  // only, and were most of a point light's cost when computed every frame.
  std::vector<CarriedPolygonFrame> frames_;
  // The samples' light from the area lights, worked out again only when they
  // change.
  AreaLightCache area_cache_;
  // The samples' kept shadows, with shadow_frames above 1.
  std::optional<ShadowBudget> shadows_;
  std::size_t last_light_count_ = 0;
  // The current frame's lights, set by solve() for the direct-light pass.
  const std::vector<Light>* lights_ = nullptr;
  const std::vector<AreaLight>* area_ = nullptr;
  std::vector<glm::vec3> first_hit_, indirect_, exitance_, sample_irradiance_;
  std::vector<float> record_;
  std::vector<double> pass_seconds_;
  FrameGraph graph_;
};

}  // namespace bounce
