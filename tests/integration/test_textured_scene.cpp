// The shipped textured-floor scene through the CLI: the bake reads its
// texture without a warning, times the texture stage in the manifest, and
// its floor patches reflect the texture's mean (an 8 x 8 checker of two
// sRGB colours, decoded here independently of the loader). Its fence is cut
// by an alpha mask (map_d) of which exactly half is solid: the bake carries
// half its area, counts the rest as cut away, and says so in the manifest.
// The textured-lamp scene's lamp emits through a half-black emissive
// texture: its patches emit half the untextured lamp's light.
#include <cmath>
#include <initializer_list>

#include "cli_harness.h"
#include "folder/bake_reader.h"

namespace bounce::itest {
namespace {

double decode(int byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// `bounce bake` of `scene` into `out` (the dense matrix and no final gather:
// what these tests read); it must succeed without a warning naming any of
// `words`.
void bake_into(const std::string& scene, const fs::path& out, const TempDir& tmp,
               std::initializer_list<const char*> words) {
  const RunResult r = run({"bake", scene, "--codec", "dense", "--final-gather-rays", "0", "--quiet",
                           "--out", out.string()},
                          tmp.path());
  ASSERT_EQ(r.exit_code, 0) << r;
  for (const std::string& w : lines_starting_with(r.err, "bounce: warning"))
    for (const char* word : words) EXPECT_FALSE(contains(w, word)) << w;
}

TEST(TexturedScene, FloorPatchesReflectTheTexturesMean) {
  TempDir tmp;
  const fs::path out = tmp.path() / "bake";
  ASSERT_NO_FATAL_FAILURE(bake_into(scene("textured-floor"), out, tmp, {"texture", "checker"}));

  const json m = read_manifest(out);
  bool timed = false;
  for (const json& stage : m["stages"]) timed = timed || stage["name"] == "texture";
  EXPECT_TRUE(timed) << m["stages"].dump(2);

  const LoadedBake b = BakeReader::read(out);
  // Mesh 0 is the floor (first in the OBJ), Kd 0.9 times the checker.
  const glm::dvec3 expected = 0.45 * (glm::dvec3(decode(224), decode(96), decode(64)) +
                                      glm::dvec3(decode(48), decode(128), decode(192)));
  glm::dvec3 sum(0.0);
  double area = 0.0;
  for (const Patch& p : b.patches.patches) {
    if (p.mesh != 0) continue;
    sum += static_cast<double>(p.area) * glm::dvec3(p.albedo);
    area += static_cast<double>(p.area);
  }
  ASSERT_NEAR(area, 4.0, 1e-2);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(sum[k] / area, expected[k], 3e-3) << "channel " << k;
}

TEST(TexturedScene, FencePatchesCarryTheSolidHalfOfIt) {
  TempDir tmp;
  const fs::path out = tmp.path() / "bake";
  ASSERT_NO_FATAL_FAILURE(bake_into(scene("textured-floor"), out, tmp, {"mask", "fence"}));
  const json m = read_manifest(out);
  EXPECT_EQ(m["scene"]["masked_materials"].get<int>(), 1);
  // The fence is 2 x 1, one-sided: 1 cut away, 1 carried (the lattice of
  // mask lookups per carried polygon measures it to a few tenths of a percent).
  EXPECT_NEAR(m["sampling"]["cut_away_area"].get<double>(), 1.0, 0.02);
  const LoadedBake b = BakeReader::read(out);
  double fence = 0.0;
  for (const Patch& p : b.patches.patches)
    if (p.mesh == 2) fence += static_cast<double>(p.area);  // the OBJ's third object
  EXPECT_NEAR(fence, 1.0, 0.02);
  EXPECT_NEAR(fence + m["sampling"]["cut_away_area"].get<double>(), 2.0, 1e-3);
}

// The shipped textured-lamp scene: its 1 x 1 lamp emits Ke = 4 through a
// texture white on one half and black on the other, so its patches emit
// half of Ke x area in all, and more on the lit half than on the dark one.
TEST(TexturedScene, LampPatchesEmitTheEmissiveTexturesMean) {
  TempDir tmp;
  const fs::path out = tmp.path() / "bake";
  ASSERT_NO_FATAL_FAILURE(bake_into(scene("textured-lamp"), out, tmp, {"texture", "half-lit"}));
  const LoadedBake b = BakeReader::read(out);
  double area = 0.0, power = 0.0, lit = 0.0, dark = 0.0;
  for (const Patch& p : b.patches.patches) {
    if (p.mesh != 1) continue;  // the lamp, second in the OBJ
    area += static_cast<double>(p.area);
    power += static_cast<double>(p.area) * static_cast<double>(p.emission.r);
    (p.position.x < 0.0f ? lit : dark) += static_cast<double>(p.area) * p.emission.r;
  }
  ASSERT_NEAR(area, 1.0, 1e-2);
  EXPECT_NEAR(power, 0.5 * 4.0, 0.02);
  EXPECT_GT(lit, 3.0 * dark);
}

}  // namespace
}  // namespace bounce::itest
