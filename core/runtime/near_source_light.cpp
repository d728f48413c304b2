#include "runtime/near_source_light.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <string>

#include "base/error.h"
#include "runtime/direct_light.h"

namespace bounce {

namespace {

// Each near source's irradiance from the area lights: kAreaStrata squared
// rays per emissive triangle, a spot's one (see NearSources). Source i
// seeds its jitter with i.
void near_area_irradiance(const NearSources& near, const RayTracer& tracer,
                          const std::vector<AreaLight>& area, std::vector<glm::vec3>& out) {
  const std::size_t n = near.size();
  const float eps = 10.0f * tracer.epsilon();
  // Lifted once here and once more by the light's own offset, as
  // irradiance_at() lifts the point it is given.
  std::vector<glm::vec3> lifted(n);
  for (std::size_t i = 0; i < n; ++i) lifted[i] = near.position[i] + eps * near.normal[i];
  area_irradiance_at_points(tracer, lifted, near.normal, area, kAreaStrata,
                            n - std::min(n, near.spot_count), out);
}

// The shadow rays to one light go to the tracer in batches of a few hundred
// (Embree's stream API): on Sponza's 421,838 near sources and the sun 1.5
// times as fast as one rtcOccluded1 call per ray. (Marking the batches
// coherent, or sending them as packets of 8 or 16, measured no faster.)
constexpr std::size_t kBatch = 256;

// What every batch of a frame reads.
struct NearFrame {
  const NearSources& near;
  const RayTracer* tracer;
  const std::vector<LightReach>& reach;
  ShadowBudget* budget;
  // Each light's kept visibility per source (budget only).
  const std::vector<std::uint8_t*>& kept_visibility;
  const std::vector<glm::vec3>* area_e;
  float eps;
};

// A batch's rays to one light, their unshadowed light and whose they are:
// written field by field in place (see LightReach::at).
struct BatchScratch {
  std::vector<ShadowRay> rays = std::vector<ShadowRay>(kBatch);
  std::vector<glm::vec3> value = std::vector<glm::vec3>(kBatch), e;
  std::vector<std::uint32_t> who = std::vector<std::uint32_t>(kBatch);
  std::vector<std::uint8_t> blocked = std::vector<std::uint8_t>(kBatch);
};

// Adds light l's direct light on sources lo .. hi - 1 (batch bi) to s.e.
// Without a budget, or in a batch the budget traces this frame, the rays are
// traced (and their visibility kept); else each source keeps the visibility
// it was last traced with, and one kept in shadow gets nothing.
void add_light_to_batch(const NearFrame& f, std::size_t l, std::size_t bi, std::size_t lo,
                        std::size_t hi, BatchScratch& s) {
  const bool trace = !f.budget || f.budget->traced(l, bi);
  std::uint8_t* const kept = f.budget ? f.kept_visibility[l] : nullptr;
  std::size_t m = 0;
  for (std::size_t i = lo; i < hi; ++i) {
    if (!trace && !kept[i]) continue;
    // Lifted once here and once more by the light's own offset, as
    // irradiance_at() lifts the point it is given.
    const glm::vec3 at = f.near.position[i] + f.eps * f.near.normal[i];
    if (!f.reach[l].at(at, f.near.normal[i], f.eps, s.rays[m], s.value[m])) continue;
    if (trace)
      s.who[m++] = static_cast<std::uint32_t>(i - lo);
    else
      s.e[i - lo] += s.value[m];
  }
  if (!trace) return;
  f.tracer->occluded(s.rays.data(), m, s.blocked.data());
  for (std::size_t k = 0; k < m; ++k) {
    if (!s.blocked[k]) s.e[s.who[k]] += s.value[k];
    if (kept) kept[lo + s.who[k]] = s.blocked[k] ? 0 : 1;
  }
}

}  // namespace

void light_near_sources(const NearSources& near, const RayTracer* tracer,
                        const std::vector<Light>& lights, const std::vector<AreaLight>& area,
                        const std::vector<glm::vec3>& patch_indirect, float* out,
                        std::size_t stride, AreaLightCache* area_cache, ShadowBudget* budget) {
  // The area lights' part: the caller's kept one, or worked out for this
  // call alone.
  AreaLightCache this_call;
  const std::vector<glm::vec3>* area_e = nullptr;
  if (tracer && !area.empty())
    area_e = &(area_cache ? *area_cache : this_call)
                  .irradiance(near.position.data(), near.size(), area, kAreaStrata,
                              [&](auto& e) { near_area_irradiance(near, *tracer, area, e); });
  const std::size_t n = near.size();
  const std::size_t batches = (n + kBatch - 1) / kBatch;
  std::vector<LightReach> reach;
  for (const Light& light : lights) reach.emplace_back(light);
  // Sized here, before the threads.
  std::vector<std::uint8_t*> kept_visibility(lights.size(), nullptr);
  if (budget && tracer) {
    budget->begin_frame(near.position.data(), batches, lights);
    for (std::size_t l = 0; l < lights.size(); ++l)
      kept_visibility[l] = budget->visibility_of(l, n).data();
  }
  const NearFrame frame{near,
                        tracer,
                        reach,
                        tracer ? budget : nullptr,
                        kept_visibility,
                        area_e,
                        tracer ? 10.0f * tracer->epsilon() : 0.0f};
  // The first source naming a patch that is not there, checked on the
  // threads as each source is written (n: none).
  std::atomic<std::size_t> first_bad{n};
#pragma omp parallel
  {
    BatchScratch s;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t bi = 0; bi < static_cast<std::int64_t>(batches); ++bi) {
      const std::size_t lo = static_cast<std::size_t>(bi) * kBatch, hi = std::min(n, lo + kBatch);
      s.e.assign(hi - lo, glm::vec3(0.0f));
      // Each source sums its lights in order, then the area lights, as
      // irradiance_at() does, so the light is the same to the last bit.
      if (tracer) {
        for (std::size_t l = 0; l < reach.size(); ++l)
          add_light_to_batch(frame, l, static_cast<std::size_t>(bi), lo, hi, s);
        if (area_e)
          for (std::size_t i = lo; i < hi; ++i) s.e[i - lo] += (*area_e)[i];
      }
      for (std::size_t i = lo; i < hi; ++i) {
        const bool known = near.patch[i] < patch_indirect.size();
        const glm::vec3 v =
            known ? near.albedo[i] * s.e[i - lo] + patch_indirect[near.patch[i]] : glm::vec3(0.0f);
        float* o = out + i * stride;
        o[0] = v.x;
        o[1] = v.y;
        o[2] = v.z;
        if (stride == 4) o[3] = 0.0f;
        if (!known)
          for (std::size_t seen = first_bad.load();
               i < seen && !first_bad.compare_exchange_weak(seen, i);) {
          }
      }
    }
  }
  if (const std::size_t i = first_bad.load(); i < n)
    throw Error("final gather", "near source " + std::to_string(i) + " names patch " +
                                    std::to_string(near.patch[i]) + " of " +
                                    std::to_string(patch_indirect.size()));
}

}  // namespace bounce
