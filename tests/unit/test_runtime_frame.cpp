// The runtime frame through the frame graph (runtime/runtime_frame.h) against
// the direct call path (light_patches: direct_irradiance, first_bounce, the
// multiply, the sum), with aliasing on and off, and consecutive frames
// against fresh ones (no stale transient data between frames).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <span>

#include "bake/bake.h"
#include "base/error.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_lights.h"
#include "runtime/dense_transport.h"
#include "runtime/patch_lighting.h"
#include "runtime/runtime_frame.h"
#include "test_scenes.h"

namespace bounce {
namespace {

// A coloured closed box with a small emissive quad under its ceiling (an
// area light) so that both kinds of light and the emission term are used.
Scene lit_box() {
  Scene s = test_scenes::furnace_box(glm::vec3(0.7f, 0.5f, 0.3f), glm::vec3(0.0f));
  test_scenes::add_quad(s, "lamp", {0.4f, 0.95f, 0.4f}, {0.6f, 0.95f, 0.4f}, {0.6f, 0.95f, 0.6f},
                        {0.4f, 0.95f, 0.6f}, glm::vec3(0.5f), glm::vec3(4.0f, 3.0f, 2.0f));
  return s;
}

struct Fixture {
  Scene scene = lit_box();
  BakeResult bake;
  RayTracer tracer{scene};
  std::vector<AreaLight> area = area_lights(scene);
  IndirectMultiply multiply;

  Fixture() {
    BakeSettings s;
    s.voxel_resolution = 6;
    s.codec = CodecChoice::Dense;
    s.transport.bounces = TransportSettings::kInfiniteBounces;
    s.transport.backend = TransportSettings::Backend::OpenBLAS;
    s.pictures = false;
    Diagnostics d;
    Progress progress;
    bake = Baker(scene, s, d).run(progress);
    std::vector<const float*> m;
    for (const ChannelTransport& c : bake.transport.channels) m.push_back(c.t.data());
    const auto map = bake.probe.channel_of_rgb;
    const std::size_t n = bake.transport.n;
    multiply = [m, map, n](const std::vector<glm::vec3>& b, std::vector<glm::vec3>& y) {
      dense_indirect(m, n, map, b, y);
    };
  }
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

Light point(glm::vec3 at) {
  Light l;
  l.name = "point";
  l.position = at;
  l.color = glm::vec3(1.0f, 0.9f, 0.8f);
  l.intensity = 2.0f;
  return l;
}

double largest(const std::vector<glm::vec3>& v) {
  double m = 0.0;
  for (const glm::vec3& x : v)
    m = std::max({m, double{std::abs(x.r)}, double{std::abs(x.g)}, double{std::abs(x.b)}});
  return m;
}

// The graph's frame equals light_patches. E and b are the same float
// operations in the same order: equal exactly. T b and the exitance come from
// the same multiply on the same b; allow float32 rounding (a few ulps of the
// largest value) in case the BLAS splits the sums differently between calls.
void expect_same(const RuntimeFrame& frame, const PatchLighting& want) {
  const std::size_t n = want.irradiance.size();
  ASSERT_EQ(frame.size(), n);
  ASSERT_EQ(frame.record().size(), 9 * n);
  const double tol_indirect = 1e-6 * largest(want.indirect);
  const double tol_exitance = 1e-6 * largest(want.exitance);
  for (std::size_t p = 0; p < n; ++p) {
    for (glm::length_t k = 0; k < 3; ++k) {
      const auto i = static_cast<std::size_t>(k);
      ASSERT_EQ(frame.record()[9 * p + i], want.irradiance[p][k]) << "E, patch " << p;
      ASSERT_EQ(frame.record()[9 * p + 3 + i], want.first_hit[p][k]) << "b, patch " << p;
      ASSERT_EQ(frame.first_hit()[p][k], want.first_hit[p][k]) << "b, patch " << p;
      ASSERT_NEAR(frame.record()[9 * p + 6 + i], want.indirect[p][k], tol_indirect) << p;
      ASSERT_NEAR(frame.indirect()[p][k], want.indirect[p][k], tol_indirect) << p;
      ASSERT_NEAR(frame.exitance()[p][k], want.exitance[p][k], tol_exitance) << p;
    }
  }
}

TEST(RuntimeFrame, GraphSolveEqualsTheDirectCallPathWithAndWithoutAliasing) {
  const Fixture& f = fixture();
  const std::vector<Light> lights = {point({0.3f, 0.5f, 0.6f})};
  const PatchLighting want =
      light_patches(f.tracer, f.bake.samples, f.bake.patches, lights, f.area, f.multiply);
  ASSERT_GT(largest(want.irradiance), 0.0);
  ASSERT_GT(largest(want.indirect), 0.0);
  for (bool alias : {true, false}) {
    SCOPED_TRACE(alias ? "aliased" : "unaliased");
    RuntimeFrameSettings s;
    s.alias = alias;
    RuntimeFrame frame(f.tracer, f.bake.samples, f.bake.patches, f.multiply, s);
    frame.solve(lights, f.area);
    expect_same(frame, want);
    // The graph's arena never exceeds the transients laid end to end (E, b
    // and T b: n colours each, rounded up to the alignment).
    EXPECT_LE(frame.transient_bytes(), frame.unaliased_transient_bytes());
    EXPECT_GE(frame.unaliased_transient_bytes(), f.bake.patches.size() * sizeof(glm::vec3));
    EXPECT_EQ(frame.pass_seconds().size(), frame.graph().passes().size());
  }
}

TEST(RuntimeFrame, ConsecutiveFramesEqualFreshFrames) {
  const Fixture& f = fixture();
  const std::vector<Light> a = {point({0.2f, 0.4f, 0.3f})};
  const std::vector<Light> b = {point({0.8f, 0.6f, 0.7f}), point({0.5f, 0.2f, 0.5f})};
  const std::vector<AreaLight> none;
  RuntimeFrame frame(f.tracer, f.bake.samples, f.bake.patches, f.multiply);
  const glm::vec3* b_memory = frame.first_hit().data();
  const glm::vec3* indirect_memory = frame.indirect().data();
  // a with the lamp, then b without it, then a again: each equals a fresh
  // solve of its own lights.
  frame.solve(a, f.area);
  expect_same(frame,
              light_patches(f.tracer, f.bake.samples, f.bake.patches, a, f.area, f.multiply));
  frame.solve(b, none);
  expect_same(frame, light_patches(f.tracer, f.bake.samples, f.bake.patches, b, none, f.multiply));
  frame.solve(a, f.area);
  expect_same(frame,
              light_patches(f.tracer, f.bake.samples, f.bake.patches, a, f.area, f.multiply));
  // No darkness leaks either: no lights at all gives no light at all.
  frame.solve({}, none);
  for (std::size_t p = 0; p < frame.size(); ++p) {
    ASSERT_EQ(frame.indirect()[p], glm::vec3(0.0f)) << p;
    ASSERT_EQ(frame.exitance()[p], f.bake.patches.patches[p].emission) << p;
  }
  // The persistent buffers were not reallocated by any frame.
  EXPECT_EQ(frame.first_hit().data(), b_memory);
  EXPECT_EQ(frame.indirect().data(), indirect_memory);
}

TEST(RuntimeFrame, WithoutRecordingKeepsTheSameExitance) {
  const Fixture& f = fixture();
  const std::vector<Light> lights = {point({0.6f, 0.3f, 0.4f})};
  RuntimeFrameSettings s;
  s.record = false;
  RuntimeFrame frame(f.tracer, f.bake.samples, f.bake.patches, f.multiply, s);
  frame.solve(lights, f.area);
  EXPECT_TRUE(frame.record().empty());
  const PatchLighting want =
      light_patches(f.tracer, f.bake.samples, f.bake.patches, lights, f.area, f.multiply);
  const double tol = 1e-6 * largest(want.exitance);
  for (std::size_t p = 0; p < frame.size(); ++p)
    for (glm::length_t k = 0; k < 3; ++k)
      ASSERT_NEAR(frame.exitance()[p][k], want.exitance[p][k], tol) << p;
}

// b and T b live in the arena with E: E (dead after "record direct") and T b
// (born in "indirect product") share one range. The arena is exactly the
// allocator's peak, which is the max-live bound (two colour buffers), below
// the three of the unaliased layout; the aliased and unaliased frames compute
// the same bits; with every dead transient overwritten by NaN after each
// pass (and the arena NaN before the first), no NaN reaches any output, so
// no pass read memory another live buffer had overwritten.
TEST(RuntimeFrame, TransientsShareTheArenaAndNeverClobberLiveData) {
  const Fixture& f = fixture();
  std::vector<const float*> m;
  for (const ChannelTransport& c : f.bake.transport.channels) m.push_back(c.t.data());
  const auto map = f.bake.probe.channel_of_rgb;
  const std::size_t n = f.bake.transport.n;
  const IndirectMultiplySpan into = [m, map, n](std::span<const glm::vec3> b,
                                                std::span<glm::vec3> y) {
    dense_indirect(m, n, map, b, y);
  };
  const std::vector<Light> lights = {point({0.3f, 0.6f, 0.4f})};
  const PatchLighting want =
      light_patches(f.tracer, f.bake.samples, f.bake.patches, lights, f.area, f.multiply);
  const std::size_t colour = (n * sizeof(glm::vec3) + 255) / 256 * 256;
  std::vector<std::vector<glm::vec3>> exitance, indirect;
  for (bool alias : {true, false}) {
    SCOPED_TRACE(alias ? "aliased" : "unaliased");
    RuntimeFrameSettings s;
    s.alias = alias;
    s.poison_dead_transients = true;
    RuntimeFrame frame(f.tracer, f.bake.samples, f.bake.patches, into, s);
    frame.solve(lights, f.area);
    expect_same(frame, want);
    for (const float x : frame.record()) ASSERT_FALSE(std::isnan(x));
    EXPECT_EQ(frame.graph().arena_bytes(), frame.transient_bytes());
    EXPECT_EQ(frame.unaliased_transient_bytes(), 3 * colour);
    EXPECT_EQ(frame.transient_bytes(), alias ? 2 * colour : 3 * colour);
    if (alias) {
      EXPECT_EQ(frame.transient_bytes(), frame.graph().max_live_transient_bytes());
    }
    exitance.push_back(frame.exitance());
    indirect.push_back(frame.indirect());
  }
  for (std::size_t p = 0; p < n; ++p) {
    ASSERT_EQ(exitance[0][p], exitance[1][p]) << p;
    ASSERT_EQ(indirect[0][p], indirect[1][p]) << p;
  }
  // The lean set-up of `bounce solve` (no published copies) and the
  // vector-multiply adapter give the same record.
  RuntimeFrameSettings lean;
  lean.publish = false;
  lean.poison_dead_transients = true;
  RuntimeFrame a(f.tracer, f.bake.samples, f.bake.patches, into, lean);
  RuntimeFrame b(f.tracer, f.bake.samples, f.bake.patches, f.multiply, lean);
  a.solve(lights, f.area);
  b.solve(lights, f.area);
  EXPECT_TRUE(a.first_hit().empty());
  EXPECT_TRUE(a.indirect().empty());
  ASSERT_EQ(a.record().size(), 9 * n);
  for (std::size_t i = 0; i < a.record().size(); ++i) {
    ASSERT_FALSE(std::isnan(a.record()[i])) << i;
    ASSERT_EQ(a.record()[i], b.record()[i]) << i;
  }
  EXPECT_EQ(a.transient_bytes(), 2 * colour);
}

TEST(RuntimeFrame, PatchesFromOtherSamplesAreAnError) {
  const Fixture& f = fixture();
  const SampleSet empty;
  EXPECT_THROW(RuntimeFrame(f.tracer, empty, f.bake.patches, f.multiply), Error);
  EXPECT_THROW(RuntimeFrame(f.tracer, f.bake.samples, f.bake.patches, IndirectMultiply{}), Error);
  EXPECT_THROW(RuntimeFrame(f.tracer, f.bake.samples, f.bake.patches, IndirectMultiplySpan{}),
               Error);
}

}  // namespace
}  // namespace bounce
