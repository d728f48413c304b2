// A patch's first-hit light as the scene sees it (runtime/seen_first_hit.h):
// the weighted mean of its samples' own light, held against hand
// arithmetic; a bake's final gather hands its seen weights to the patches,
// and the light the multi-bounce transport multiplies is then that mean.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bake/bake.h"
#include "base/error.h"
#include "raytrace/ray_tracer.h"
#include "runtime/patch_lighting.h"
#include "runtime/runtime_frame.h"
#include "runtime/seen_first_hit.h"
#include "test_scenes.h"

namespace bounce {
namespace {

// Three samples in two patches: patch 0 holds samples 0 and 1, patch 1
// sample 2.
struct TwoPatches {
  SampleSet samples;
  PatchSet patches;
  TwoPatches() {
    const glm::vec3 albedo[3] = {{0.8f, 0.6f, 0.4f}, {0.2f, 0.3f, 0.5f}, {0.5f, 0.5f, 0.5f}};
    for (const glm::vec3& a : albedo) {
      Sample s{};
      s.normal = glm::vec3(0, 1, 0);
      s.albedo = a;
      s.area = 1.0f;
      samples.samples.push_back(s);
    }
    patches.add_patch(samples.samples, {0, 1});
    patches.add_patch(samples.samples, {2});
  }
};

TEST(SeenFirstHit, IsTheSamplesOwnLightWeightedAsTheRaysSawThem) {
  TwoPatches t;
  const std::vector<glm::vec3> sample_e = {{4, 4, 4}, {0, 1, 2}, {3, 2, 1}};
  // The patches' area-mean irradiance (what the frame computes beside).
  const std::vector<glm::vec3> patch_e = {{2, 2.5f, 3}, {3, 2, 1}};
  std::vector<glm::vec3> b(2);
  // No weights: albedo x the area mean.
  seen_first_hit(t.samples, t.patches, patch_e, sample_e, b);
  for (std::size_t p = 0; p < 2; ++p)
    for (int c = 0; c < 3; ++c)
      EXPECT_FLOAT_EQ(b[p][c], t.patches.patches[p].albedo[c] * patch_e[p][c]) << p;
  // Three quarters of the rays on sample 0 (lit), a quarter on sample 1;
  // patch 1 was not read through patch entries (weights 0).
  t.patches.member_seen_weight = {0.75f, 0.25f, 0.0f};
  seen_first_hit(t.samples, t.patches, patch_e, sample_e, b);
  const glm::vec3 expected0(0.75f * 0.8f * 4 + 0.25f * 0.2f * 0,
                            0.75f * 0.6f * 4 + 0.25f * 0.3f * 1,
                            0.75f * 0.4f * 4 + 0.25f * 0.5f * 2);
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(b[0][c], expected0[c]) << c;
    EXPECT_FLOAT_EQ(b[1][c], t.patches.patches[1].albedo[c] * patch_e[1][c]) << c;
  }
  // Seen weights need every sample's own irradiance.
  EXPECT_THROW(seen_first_hit(t.samples, t.patches, patch_e, {}, b), Error);
}

TEST(SeenFirstHit, GatherWeightsGoToThePatchesMembers) {
  TwoPatches t;
  FinalGather g;
  g.patches = 2;
  g.seen_first = {0, 2, 2};
  g.seen_sample = {1, 0};
  g.seen_weight = {0.4f, 0.6f};
  set_seen_weights(g, t.patches, "gather");
  EXPECT_EQ(t.patches.member_seen_weight, (std::vector<float>{0.6f, 0.4f, 0.0f}));
  // A sample of another patch: one error naming the patch and the sample.
  g.seen_sample = {2, 0};
  try {
    set_seen_weights(g, t.patches, "gather");
    ADD_FAILURE() << "a sample outside its patch was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("patch 0's seen weights name sample 2"), std::string::npos)
        << e.what();
  }
  // Row starts that do not fit the entries.
  g.seen_sample = {1, 0};
  g.seen_first = {0, 3, 2};
  EXPECT_THROW(set_seen_weights(g, t.patches, "gather"), Error);
  // No seen weights: none on the patches either.
  set_seen_weights(FinalGather{}, t.patches, "gather");
  EXPECT_TRUE(t.patches.member_seen_weight.empty());
}

TEST(SeenFirstHit, TheTransportMultipliesTheLightTheBakesGatherSaw) {
  // A floor half in a board's shadow, a wall at its far edge, a sun: the
  // shadow's edge runs through patches, so their lit and shaded samples
  // differ. A bake with its final gather: the patches carry the gather's seen
  // weights, and b, the vector T multiplies, is the seen-weighted mean of the
  // samples' albedo x E, computed here in double from the frame's own E per
  // sample.
  Scene scene;
  test_scenes::add_quad(scene, "floor", {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});
  test_scenes::add_quad(scene, "board", {-1.5f, 0.5f, -1.5f}, {-1.5f, 0.5f, 1.5f}, {0, 0.5f, 1.5f},
                        {0, 0.5f, -1.5f});
  test_scenes::add_quad(scene, "wall", {1, 0, -1}, {1, 0, 1}, {1, 0.5f, 1}, {1, 0.5f, -1});
  scene.lights.push_back({Light::Type::Directional, "sun", glm::vec3(0.0f),
                          glm::vec3(0.3f, -1.0f, 0.1f), glm::vec3(1.0f), 1.0f});
  BakeSettings s;
  s.voxel_resolution = 3;
  s.codec = CodecChoice::Dense;
  s.transport.backend = TransportSettings::Backend::OpenBLAS;
  s.pictures = false;
  Diagnostics d;
  Progress progress;
  const BakeResult bake = Baker(scene, s, d).run(progress);
  ASSERT_FALSE(bake.vertex_gather.seen_first.empty());
  ASSERT_EQ(bake.patches.member_seen_weight.size(), bake.patches.member_samples.size());
  const RayTracer tracer(scene);
  std::vector<glm::vec3> multiplied;
  const PatchLighting l =
      light_patches(tracer, bake.samples, bake.patches, scene.lights, {},
                    [&multiplied](const std::vector<glm::vec3>& b, std::vector<glm::vec3>& tb) {
                      multiplied = b;
                      tb.assign(b.size(), glm::vec3(0.0f));
                    });
  ASSERT_EQ(multiplied.size(), bake.patches.size());
  std::size_t seen_patches = 0, differ = 0;
  for (std::size_t p = 0; p < bake.patches.size(); ++p) {
    glm::dvec3 sum(0.0);
    double total = 0.0;
    for (std::uint32_t m = bake.patches.member_first[p]; m < bake.patches.member_first[p + 1];
         ++m) {
      const std::uint32_t smp = bake.patches.member_samples[m];
      const double w = bake.patches.member_seen_weight[m];
      sum +=
          w * glm::dvec3(bake.samples.samples[smp].albedo) * glm::dvec3(l.sample_irradiance[smp]);
      total += w;
    }
    const glm::dvec3 area_b =
        glm::dvec3(bake.patches.patches[p].albedo) * glm::dvec3(l.irradiance[p]);
    const glm::dvec3 expected = total > 0.0 ? sum : area_b;
    seen_patches += total > 0.0 ? 1 : 0;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(multiplied[p][c], expected[c], 1e-5 * (1.0 + expected[c])) << p;
    if (glm::length(expected - area_b) > 1e-3 * (1.0 + glm::length(area_b))) ++differ;
  }
  EXPECT_GT(seen_patches, 0u);
  EXPECT_GT(differ, 0u) << "no patch's seen b differs from its area mean: the test cannot tell";
  // The run-time frame lights the patches the same way.
  RuntimeFrame frame(tracer, bake.samples, bake.patches,
                     [](const std::vector<glm::vec3>& b, std::vector<glm::vec3>& tb) {
                       tb.assign(b.size(), glm::vec3(0.0f));
                     });
  frame.solve(scene.lights, {});
  ASSERT_EQ(frame.first_hit().size(), l.first_hit.size());
  for (std::size_t p = 0; p < l.first_hit.size(); ++p)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(frame.first_hit()[p][c], l.first_hit[p][c], 1e-6 * (1.0 + l.first_hit[p][c]));
}

}  // namespace
}  // namespace bounce
