#include "runtime/patch_lighting.h"

#include <chrono>

#include "runtime/direct_light.h"
#include "runtime/seen_first_hit.h"

namespace bounce {

PatchLighting light_patches(const RayTracer& tracer, const SampleSet& samples,
                            const PatchSet& patches, const std::vector<Light>& lights,
                            const std::vector<AreaLight>& area, const IndirectMultiply& multiply) {
  using Clock = std::chrono::steady_clock;
  PatchLighting l;
  auto t = Clock::now();
  l.irradiance.assign(patches.size(), glm::vec3(0.0f));
  l.sample_irradiance.assign(samples.samples.size(), glm::vec3(0.0f));
  direct_irradiance(tracer, samples, patches, lights, area, 4, l.irradiance, l.sample_irradiance);
  l.first_hit.resize(patches.size());
  seen_first_hit(samples, patches, l.irradiance, l.sample_irradiance, l.first_hit);
  l.seconds_direct = std::chrono::duration<double>(Clock::now() - t).count();
  t = Clock::now();
  multiply(l.first_hit, l.indirect);
  l.seconds_indirect = std::chrono::duration<double>(Clock::now() - t).count();
  l.exitance.resize(patches.size());
  for (std::size_t p = 0; p < patches.size(); ++p)
    l.exitance[p] = patches.patches[p].emission + l.first_hit[p] + l.indirect[p];
  return l;
}

}  // namespace bounce
