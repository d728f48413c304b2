// The runtime on whole baked scenes: the furnace's analytic answer through
// the compressed product, no light gives no indirect light, and a mirrored
// light gives the mirrored result.
#include <gtest/gtest.h>

#include "bake/bake.h"
#include "raytrace/ray_tracer.h"
#include "runtime/compressed_transport.h"
#include "runtime/dense_transport.h"
#include "runtime/patch_lighting.h"
#include "test_scenes.h"

namespace bounce {
namespace {

BakeResult bake(const Scene& scene, int voxel, CodecChoice codec) {
  BakeSettings s;
  s.voxel_resolution = voxel;
  s.codec = codec;
  s.transport.bounces = TransportSettings::kInfiniteBounces;
  s.transport.backend = TransportSettings::Backend::OpenBLAS;
  s.pictures = false;
  Diagnostics d;
  Progress progress;
  return Baker(scene, s, d).run(progress);
}

IndirectMultiply dense_multiply(const BakeResult& r) {
  std::vector<const float*> m;
  for (const ChannelTransport& c : r.transport.channels) m.push_back(c.t.data());
  const auto map = r.probe.channel_of_rgb;
  const std::size_t n = r.transport.n;
  return [m, map, n](const std::vector<glm::vec3>& b, std::vector<glm::vec3>& y) {
    dense_indirect(m, n, map, b, y);
  };
}

TEST(RuntimeScenes, FurnaceGivesTheAnalyticAnswerThroughTheCompressedProduct) {
  // Closed box, albedo 0.5: a unit first hit everywhere comes back as
  // sum_h 0.5^h = 1 of indirect light on every patch (rows of F sum to 1
  // within ~1%, which T(inf) amplifies to ~2%).
  const BakeResult r = bake(test_scenes::furnace_box(), 6, CodecChoice::LightWeighted);
  ASSERT_TRUE(r.storage.compressed.has_value());
  const CompressedTransport compressed(*r.storage.compressed, r.probe.channel_of_rgb);
  const std::vector<glm::vec3> b(r.patches.size(), glm::vec3(1.0f));
  std::vector<glm::vec3> y, exact;
  compressed.multiply(b, y);
  dense_multiply(r)(b, exact);
  double worst = 0.0;
  for (std::size_t p = 0; p < y.size(); ++p) {
    EXPECT_NEAR(exact[p].r, 1.0, 0.03) << p;
    worst = std::max(worst, std::abs(static_cast<double>(y[p].r) - exact[p].r));
  }
  // The compressed product adds the codec's error: a uniform b averages it
  // over each row, well inside the relative Frobenius error the bake measured.
  EXPECT_LT(worst, std::max(0.01, r.storage.errors.matrix.rel_frobenius));
}

TEST(RuntimeScenes, NoLightGivesNoIndirectLightAndAMirroredLightAMirroredResult) {
  // The furnace's cube without emission, lit by one point light left or
  // right of the centre: the left wall in one case receives what the right
  // wall receives in the other.
  const Scene box = test_scenes::furnace_box(glm::vec3(0.6f), glm::vec3(0.0f));
  const BakeResult r = bake(box, 6, CodecChoice::Dense);
  const RayTracer tracer(box);
  const IndirectMultiply multiply = dense_multiply(r);
  const PatchLighting dark = light_patches(tracer, r.samples, r.patches, {}, {}, multiply);
  for (const glm::vec3& v : dark.indirect) ASSERT_EQ(v, glm::vec3(0.0f));

  auto wall_light = [&](float light_x) {
    Light l;
    l.position = {light_x, 0.5f, 0.5f};
    const PatchLighting lit = light_patches(tracer, r.samples, r.patches, {l}, {}, multiply);
    // Area-weighted indirect light on the walls facing +x (at x = 0) and -x.
    glm::dvec2 walls(0.0);
    for (std::size_t p = 0; p < r.patches.size(); ++p) {
      const Patch& patch = r.patches.patches[p];
      if (patch.normal.x > 0.9f) walls.x += patch.area * lit.indirect[p].g;
      if (patch.normal.x < -0.9f) walls.y += patch.area * lit.indirect[p].g;
    }
    return walls;
  };
  const glm::dvec2 left = wall_light(0.3f), right = wall_light(0.7f);
  EXPECT_GT(left.x, left.y) << "the wall nearer the light gets more";
  // Mirror images up to the asymmetry of the jittered samples and clusters.
  EXPECT_NEAR(left.x, right.y, 0.01 * left.x);
  EXPECT_NEAR(left.y, right.x, 0.01 * left.y);
}

}  // namespace
}  // namespace bounce
