// The light on a bake's patches as the studio's patch view shows it
// (bake/bake_patch_light.h), against the computations the view made itself
// before they moved into the core: the same numbers, bit for bit.
#include <gtest/gtest.h>

#include <iterator>

#include "bake/bake_patch_light.h"
#include "base/error.h"
#include "compress/codec.h"
#include "compressed_cornell_bake.h"
#include "runtime/dense_transport.h"
#include "runtime/direct_light.h"

namespace bounce {
namespace {

std::vector<const float*> pointers(const std::vector<std::vector<float>>& m) {
  std::vector<const float*> out;
  for (const auto& c : m) out.push_back(c.data());
  return out;
}

std::vector<float> areas(const LoadedBake& b) {
  std::vector<float> area;
  for (const Patch& p : b.patches.patches) area.push_back(p.area);
  return area;
}

TEST(BakePatchLight, TheBakeHasWhatTheViewNeeds) {
  const LoadedBake& b = test::compressed_cornell_bake();
  ASSERT_TRUE(b.compressed);
  ASSERT_FALSE(b.dense.empty());
  ASSERT_FALSE(b.probe.first_hit.empty());
  EXPECT_EQ(light_set_count(b), 1 + b.probe.first_hit.size());
}

TEST(BakePatchLight, LightSetsAreTheScenesLightsThenEachEvaluationLight) {
  const LoadedBake& b = test::compressed_cornell_bake();
  const std::size_t n = b.size();
  // Set 0 as the view summed it: the scene's own lights, and the area light
  // (the last entry) when there is one.
  std::vector<glm::vec3> want(n, glm::vec3(0.0f));
  const std::size_t scene_lights = b.manifest.at("scene").at("lights").size();
  ASSERT_GT(scene_lights, 0u);
  const bool area =
      b.probe.first_hit.size() > scene_lights + kEvaluationPointLights + std::size(kEvaluationSuns);
  for (std::size_t l = 0; l < b.probe.first_hit.size(); ++l)
    if (l < scene_lights || (area && l + 1 == b.probe.first_hit.size()))
      for (std::size_t p = 0; p < n; ++p) want[p] += b.probe.first_hit[l][p];
  EXPECT_EQ(light_set_first_hit(b, 0), want);
  for (std::size_t k = 1; k < light_set_count(b); ++k)
    EXPECT_EQ(light_set_first_hit(b, k), b.probe.first_hit[k - 1]) << "set " << k;
  EXPECT_THROW(light_set_first_hit(b, light_set_count(b)), Error);
}

TEST(BakePatchLight, RadiosityIsEmissionPlusFirstHitPlusIndirect) {
  const LoadedBake& b = test::compressed_cornell_bake();
  const std::size_t n = b.size();
  std::vector<glm::vec3> indirect;
  dense_indirect(pointers(b.dense), n, b.channel_of_rgb, b.probe.first_hit[0], indirect);
  const PatchRadiosity r = patch_radiosity(b);
  ASSERT_TRUE(r.lit);
  ASSERT_EQ(r.radiosity.size(), n);
  for (std::size_t p = 0; p < n; ++p) {
    glm::vec3 want = b.patches.patches[p].emission;
    want += b.probe.first_hit[0][p] + indirect[p];
    ASSERT_EQ(r.radiosity[p], want) << "patch " << p;
  }
}

TEST(BakePatchLight, WithoutTheExactMatrixRadiosityIsTheEmission) {
  LoadedBake b = test::compressed_cornell_bake();
  b.dense.clear();
  const PatchRadiosity r = patch_radiosity(b);
  EXPECT_FALSE(r.lit);
  for (std::size_t p = 0; p < b.size(); ++p)
    EXPECT_EQ(r.radiosity[p], b.patches.patches[p].emission);
}

TEST(BakePatchLight, IndirectErrorIsTheDecodedMatrixAgainstTheExactOne) {
  const LoadedBake& b = test::compressed_cornell_bake();
  const std::size_t n = b.size();
  const std::vector<std::vector<float>> decoded = decode_compressed(b);
  ASSERT_EQ(decoded.size(), static_cast<std::size_t>(b.compressed->channels));
  std::vector<float> one(n * n);
  for (int c = 0; c < b.compressed->channels; ++c) {
    decompress_channel(*b.compressed, c, one.data());
    EXPECT_EQ(decoded[static_cast<std::size_t>(c)], one) << "channel " << c;
  }
  for (std::size_t set : {std::size_t{0}, std::size_t{2}}) {
    const std::vector<glm::vec3> light = light_set_first_hit(b, set);
    const PatchLightError want = patch_light_error(pointers(b.dense), pointers(decoded), n,
                                                   b.channel_of_rgb, light, areas(b));
    const PatchIndirectError got = compressed_indirect_error(b, decoded, set);
    EXPECT_GT(got.error.rel_rms, 0.0);
    EXPECT_EQ(got.error.rel_rms, want.rel_rms) << "set " << set;
    EXPECT_EQ(got.error.relative, want.relative) << "set " << set;
    EXPECT_EQ(got.error.exact, want.exact) << "set " << set;
    EXPECT_FALSE(got.explanation);
  }
  // A picked patch: its row explained, as row_error_contributions does.
  const std::size_t p = n / 2;
  const PatchIndirectError got = compressed_indirect_error(b, decoded, 1, p);
  ASSERT_TRUE(got.explanation);
  const RowErrorContributions want = row_error_contributions(
      *b.compressed, pointers(b.dense), b.channel_of_rgb, b.probe.first_hit[0], p);
  EXPECT_EQ(got.explanation->patch, p);
  EXPECT_EQ(got.explanation->exact, want.exact);
  EXPECT_EQ(got.explanation->compressed, want.compressed);
  ASSERT_EQ(got.explanation->sources.size(), want.sources.size());
  for (std::size_t k = 0; k < want.sources.size(); ++k)
    EXPECT_EQ(got.explanation->sources[k].share, want.sources[k].share) << "source " << k;
  EXPECT_THROW(compressed_indirect_error(b, decoded, 0, n), Error);
}

TEST(BakePatchLight, IndirectErrorNeedsBothMatrices) {
  LoadedBake b = test::compressed_cornell_bake();
  const std::vector<std::vector<float>> decoded = decode_compressed(b);
  b.dense.clear();
  EXPECT_THROW(compressed_indirect_error(b, decoded, 0), Error);
  b.compressed.reset();
  EXPECT_THROW(decode_compressed(b), Error);
}

}  // namespace
}  // namespace bounce
