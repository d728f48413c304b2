#pragma once
// Lights a bake again, frame after frame: the one sequence every front end
// runs on a bake (`bounce solve`, `bake --reference`, the studio's preview):
//
//   pick the product T b once      runtime/transport_multiplier.h
//   light the patches              the frame graph (runtime/runtime_frame.h):
//                                  direct light E, b = albedo E, T b, exitance
//   gather to points               the final gather (runtime/final_gather.h):
//                                  the irradiance at mesh vertices or camera
//                                  pixels from the patches' reflected b + T b
//
// The tracer, samples, patches and (for a dense product) the matrices of
// the StoredTransport must outlive the Relighter. One light() at a time.
#include <chrono>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "runtime/area_light_cache.h"
#include "runtime/final_gather.h"
#include "runtime/runtime_frame.h"
#include "runtime/transport_multiplier.h"

namespace bounce {

struct RelighterSettings {
  MultiplyChoice multiply = MultiplyChoice::kAuto;
  CppLoop loop = CppLoop::kMeasured;
  RuntimeFrameSettings frame;
  // The patches' samples and the gather's near sources trace their shadow
  // rays to a light that moved over this many frames
  // (runtime/shadow_budget.h): 1, every ray in the frame it moved; k, a k-th
  // of them per frame, the light exact k frames after the light stops. It
  // replaces frame.shadow_frames. While they are spread, gather() sums a
  // k-th of the vertices' rows a frame too (runtime/gather_row_budget.h),
  // and all of them in the frame the shadows are exact again.
  int shadow_frames = 1;
};

class Relighter {
 public:
  // Throws what TransportMultiplier and RuntimeFrame throw.
  Relighter(const RayTracer& tracer, const SampleSet& samples, const PatchSet& patches,
            const StoredTransport& transport, const RelighterSettings& settings = {},
            Diagnostics* diagnostics = nullptr);
  Relighter(const Relighter&) = delete;
  Relighter& operator=(const Relighter&) = delete;

  // One frame on the patches for these lights.
  void light(const std::vector<Light>& lights, const std::vector<AreaLight>& area = {});

  // The light the patches reflect in the last frame, b + T b, per patch:
  // what the final gather sums. Read from the frame's published b and T b,
  // or from its record when it does not publish them.
  void reflected(std::vector<glm::vec3>& out) const;
  // The irradiance at the gather's points from the last frame's reflected
  // light (before any albedo); its sample sources read each sample's own b
  // plus its patch's T b. One gather at a time: it works in buffers the
  // Relighter keeps from frame to frame.
  void gather(const FinalGather& gather, std::vector<glm::vec3>& irradiance) const;
  // The same for a gather without near sources (the light probes'): it
  // leaves the near sources' shadow state, which belongs to the vertices'
  // gather, alone. Throws bounce::Error for a gather with near sources.
  void gather_far(const FinalGather& gather, std::vector<glm::vec3>& irradiance) const;

  const RuntimeFrame& frame() const { return frame_; }
  const std::string& multiply_name() const { return multiplier_.what(); }
  // What construction took: choosing and laying out the product (with the
  // loop's measurement), and building and compiling the frame graph.
  double multiply_seconds() const { return multiply_seconds_; }
  double compile_seconds() const { return compile_seconds_; }
  // Seconds the last gather spent lighting its near sources.
  double near_seconds() const { return near_seconds_; }
  // Shadow-ray batches the last gather traced to its near sources (over all
  // lights; a light that did not move traces none).
  std::size_t near_traced_batches() const { return near_shadows_.traced_batches(); }
  // The samples' and near sources' shadows are exact for the lights of the
  // last frame and gather, and the gather summed every row (always, with
  // shadow_frames 1; else once the frames and gathers since a light last
  // moved traced every batch).
  // The rows of the vertices' gather the last gather() summed.
  const GatherRowBudget& gather_rows() const { return gather_rows_; }
  bool shadows_settled() const {
    return frame_.shadows_settled() && near_shadows_.settled() && gather_rows_.settled();
  }

  // The last frame's b and T b per patch, from its published buffers or its
  // record. Throws bounce::Error when the frame keeps neither.
  void first_hit_and_indirect(std::vector<glm::vec3>& b, std::vector<glm::vec3>& tb) const;

 private:
  double multiply_seconds_ = 0.0, compile_seconds_ = 0.0;
  TransportMultiplier multiplier_;
  std::chrono::steady_clock::time_point compile_start_;
  const RayTracer& tracer_;
  const SampleSet& samples_;
  const PatchSet& patches_;
  // The last frame's lights: a gather's near sources are lit with them.
  std::vector<Light> lights_;
  std::vector<AreaLight> area_;
  mutable double near_seconds_ = 0.0;
  // The near sources' light from the area lights, kept while they and the
  // gather stay the same.
  mutable AreaLightCache near_area_cache_;
  mutable ShadowBudget near_shadows_;
  // gather()'s rows while shadows are spread, and its last product (the
  // rows a frame does not sum keep it), for the gather `gathered_for_`.
  mutable GatherRowBudget gather_rows_;
  mutable std::vector<glm::vec3> gathered_;
  mutable const FinalGather* gathered_for_ = nullptr;
  // The last frame's b + T b per patch and its samples' light, as `gather`
  // reads them, into the buffers below.
  void source_light(const FinalGather& gather) const;
  // gather()'s buffers, kept so that a frame does not allocate them again.
  mutable std::vector<glm::vec3> first_hit_, indirect_, reflected_, sample_light_;
  // Whether reflected_ (with first_hit_ and indirect_) and sample_light_
  // hold this frame's light; light() starts a frame.
  mutable bool reflected_fresh_ = false, sample_light_fresh_ = false;
  RuntimeFrame frame_;
};

}  // namespace bounce
