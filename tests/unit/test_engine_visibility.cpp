// A RayTracer whose occlusion an engine answers (raytrace/ray_tracer.h):
// the Relighter's frame over it equals the frame over Embree when the
// engine answers as Embree does, goes dark when the engine says every ray
// is blocked, and asks the engine for every shadow ray it casts.
#include <gtest/gtest.h>

#include <atomic>

#include "bake/bake.h"
#include "bake/stored_transport.h"
#include "base/error.h"
#include "furnace_bake.h"
#include "raytrace/ray_tracer.h"
#include "runtime/relighter.h"

namespace bounce {
namespace {

using test_scenes::furnace_bake;

std::vector<glm::vec3> reflected_light(const RayTracer& tracer) {
  const test_scenes::FurnaceBake& f = furnace_bake();
  RelighterSettings s;
  s.multiply = MultiplyChoice::kDense;
  Relighter r(tracer, f.bake.samples, f.bake.patches,
              stored_transport(f.bake.transport, f.bake.storage), s);
  Light lamp;
  lamp.name = "lamp";
  lamp.position = glm::vec3(0.5f, 0.6f, 0.4f);
  lamp.color = glm::vec3(1.0f, 0.9f, 0.8f);
  lamp.intensity = 2.0f;
  r.light({lamp});
  std::vector<glm::vec3> reflected;
  r.reflected(reflected);
  return reflected;
}

}  // namespace

TEST(EngineVisibility, AnEngineAnsweringAsEmbreeGivesTheSameFrame) {
  const test_scenes::FurnaceBake& f = furnace_bake();
  std::atomic<std::size_t> asked{0};
  const RayTracer engine(f.scene,
                         [&](std::span<const ShadowRay> rays, std::span<std::uint8_t> blocked) {
                           asked += rays.size();
                           f.tracer.occluded(rays.data(), rays.size(), blocked.data());
                         });
  const std::vector<glm::vec3> want = reflected_light(f.tracer);
  const std::vector<glm::vec3> got = reflected_light(engine);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t p = 0; p < got.size(); ++p) ASSERT_EQ(got[p], want[p]) << "patch " << p;
  // One shadow ray per sample to the lamp at least.
  EXPECT_GE(asked.load(), f.bake.samples.samples.size());
  double total = 0.0;
  for (const glm::vec3& c : want) total += c.r + c.g + c.b;
  EXPECT_GT(total, 0.0) << "the lamp lights nothing: the comparison would prove nothing";
}

TEST(EngineVisibility, EveryRayBlockedLeavesTheScenesDark) {
  const test_scenes::FurnaceBake& f = furnace_bake();
  const RayTracer engine(f.scene, [](std::span<const ShadowRay>, std::span<std::uint8_t> blocked) {
    std::fill(blocked.begin(), blocked.end(), std::uint8_t{1});
  });
  for (const glm::vec3& c : reflected_light(engine)) EXPECT_EQ(c, glm::vec3(0.0f));
}

TEST(EngineVisibility, ClosestHitQueriesNameTheirNeed) {
  const test_scenes::FurnaceBake& f = furnace_bake();
  EXPECT_THROW(RayTracer(f.scene, OcclusionQuery{}), Error);
  const RayTracer engine(f.scene, [](std::span<const ShadowRay>, std::span<std::uint8_t> blocked) {
    std::fill(blocked.begin(), blocked.end(), std::uint8_t{0});
  });
  EXPECT_THROW(engine.intersect(glm::vec3(0.5f), glm::vec3(0.0f, 1.0f, 0.0f)), Error);
  EXPECT_FALSE(engine.occluded(glm::vec3(0.5f), glm::vec3(0.0f, 1.0f, 0.0f), 0.0f, 1.0f));
}

}  // namespace bounce
