// The one way front ends light a bake (runtime/relighter.h,
// runtime/transport_multiplier.h): the product chosen by name and by what
// the bake holds, the frame's reflected light equal to light_patches'
// whether the frame publishes b and T b or only records them, and the
// final gather summing that light.
#include <gtest/gtest.h>

#include "bake/bake.h"
#include "bake/stored_transport.h"
#include "base/error.h"
#include "furnace_bake.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_lights.h"
#include "runtime/relighter.h"

namespace bounce {
namespace {

using test_scenes::furnace_bake;

std::vector<Light> one_point_light() {
  Light l;
  l.name = "point";
  l.position = glm::vec3(0.5f, 0.6f, 0.4f);
  l.color = glm::vec3(1.0f, 0.9f, 0.8f);
  l.intensity = 2.0f;
  return {l};
}

TEST(TransportMultiplier, ChoicesByName) {
  for (const MultiplyChoice c : {MultiplyChoice::kAuto, MultiplyChoice::kOpenCl,
                                 MultiplyChoice::kCpp, MultiplyChoice::kDense})
    EXPECT_EQ(multiply_choice_from_name(multiply_choice_name(c)), c);
  EXPECT_FALSE(multiply_choice_from_name("fastest").has_value());
}

TEST(TransportMultiplier, TakesWhatTheBakeHolds) {
  const test_scenes::FurnaceBake& f = furnace_bake();
  const StoredTransport dense = stored_transport(f.bake.transport, f.bake.storage);
  ASSERT_EQ(dense.compressed, nullptr);
  EXPECT_EQ(TransportMultiplier(dense, MultiplyChoice::kAuto, CppLoop::kMeasured)
                .what()
                .rfind("dense", 0),
            0u);
  EXPECT_EQ(TransportMultiplier(dense, MultiplyChoice::kAutoCpu, CppLoop::kMeasured)
                .what()
                .rfind("dense", 0),
            0u);
  // A compressed product of a dense bake, or a dense one of a bake without
  // its dense matrices, names the bake.
  EXPECT_THROW(TransportMultiplier(dense, MultiplyChoice::kCpp, CppLoop::kMeasured), Error);
  StoredTransport nothing = dense;
  nothing.dense.clear();
  EXPECT_THROW(TransportMultiplier(nothing, MultiplyChoice::kDense, CppLoop::kMeasured), Error);
  EXPECT_THROW(TransportMultiplier(nothing, MultiplyChoice::kAutoCpu, CppLoop::kMeasured), Error);
}

TEST(Relighter, EqualsLightPatchesPublishedOrRecorded) {
  const test_scenes::FurnaceBake& f = furnace_bake();
  const StoredTransport t = stored_transport(f.bake.transport, f.bake.storage);
  const std::vector<Light> lights = one_point_light();
  const std::vector<AreaLight> area = area_lights(f.scene);
  const PatchLighting direct =
      light_patches(f.tracer, f.bake.samples, f.bake.patches, lights, area,
                    TransportMultiplier(t, MultiplyChoice::kDense, CppLoop::kMeasured).multiply());
  for (const bool publish : {true, false}) {
    RelighterSettings s;
    s.multiply = MultiplyChoice::kDense;
    s.frame.publish = publish;
    Relighter r(f.tracer, f.bake.samples, f.bake.patches, t, s);
    r.light(lights, area);
    std::vector<glm::vec3> reflected;
    r.reflected(reflected);
    ASSERT_EQ(reflected.size(), direct.first_hit.size());
    for (std::size_t p = 0; p < reflected.size(); ++p)
      ASSERT_EQ(reflected[p], direct.first_hit[p] + direct.indirect[p]) << "patch " << p;
  }
}

TEST(Relighter, GathersTheReflectedLight) {
  const test_scenes::FurnaceBake& f = furnace_bake();
  RelighterSettings s;
  s.frame.record = false;
  Relighter r(f.tracer, f.bake.samples, f.bake.patches,
              stored_transport(f.bake.transport, f.bake.storage), s);
  r.light(one_point_light());
  // A gather with one point taking half of patch 0's light and a quarter of
  // patch 1's.
  FinalGather g;
  g.first = {0, 2};
  g.source = {0, 1};
  g.weight = {0.5f, 0.25f};
  g.patches = f.bake.patches.size();
  g.cluster_of_patch.assign(g.patches, 0);
  g.cluster_share.assign(g.patches, 1.0f / static_cast<float>(g.patches));
  g.clusters = 1;
  std::vector<glm::vec3> reflected, irradiance;
  r.reflected(reflected);
  r.gather(g, irradiance);
  ASSERT_EQ(irradiance.size(), 1u);
  const glm::vec3 expected = 0.5f * reflected[0] + 0.25f * reflected[1];
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(irradiance[0][c], expected[c], 1e-6f * expected[c]);
}

}  // namespace
}  // namespace bounce
