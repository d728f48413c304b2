// The polygons of surface each sample carries go into the bake folder
// (carried_*.npy) so that a bake read back gives the same direct light as
// the bake computed: point lights are integrated over those polygons
// (runtime/direct_light.cpp), which the samples alone cannot do. The bake's
// own first-hit vectors (lights_first_hit.npy, computed in memory during the
// bake) are the expectation.
#include <algorithm>
#include <cmath>

#include "base/diagnostics.h"
#include "cli_harness.h"
#include "folder/bake_reader.h"
#include "io/npy.h"
#include "raytrace/ray_tracer.h"
#include "runtime/direct_light.h"
#include "runtime/patch_lighting.h"
#include "scene/scene_loader.h"

namespace bounce::itest {
namespace {

// Largest |a - b| over all patches and channels, relative to the largest |b|;
// absolute when b is zero everywhere (an evaluation sun the closed box
// shadows entirely).
double relative_difference(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      diff = std::max(diff, static_cast<double>(std::abs(a[i][k] - b[i][k])));
      scale = std::max(scale, static_cast<double>(std::abs(b[i][k])));
    }
  return scale > 0.0 ? diff / scale : diff;
}

class CarriedPolygons : public ::testing::Test {
 protected:
  void SetUp() override {
    out = tmp.path() / "bake";
    const RunResult r = run({"bake", scene("cornell-box"), "--voxel", "4", "--codec", "dense",
                             "--quiet", "--out", out.string()},
                            tmp.path());
    ASSERT_EQ(r.exit_code, 0) << r;
  }
  TempDir tmp;
  fs::path out;
};

TEST_F(CarriedPolygons, BakeReadBackGivesTheBakesOwnDirectLight) {
  for (const char* file : {"carried_polygons.npy", "carried_area.npy", "carried_vertices.npy"})
    ASSERT_TRUE(fs::exists(out / file)) << file;
  LoadedBake b = BakeReader::read(out);
  ASSERT_EQ(b.samples.carried_first.size(), b.samples.samples.size() + 1);
  ASSERT_FALSE(b.samples.carried.empty());

  Diagnostics diagnostics;
  const Scene cornell = SceneLoader(diagnostics).load(scene("cornell-box"));
  const RayTracer tracer(cornell);
  const std::vector<Light> lights = evaluation_lights(cornell);
  ASSERT_GE(b.probe.first_hit.size(), lights.size());
  // Light 0 is the scene's point light under the ceiling, where evaluating
  // at the samples is far off; the others are the four evaluation lights.
  std::vector<double> with_polygons, at_samples;
  // b as the run time makes it from the bake read back (seen-weighted over
  // the samples: the bake stores its gather's seen weights).
  ASSERT_FALSE(b.patches.member_seen_weight.empty());
  const auto first_hit = [&](const Light& light) {
    return light_patches(tracer, b.samples, b.patches, {light}, {},
                         [](const std::vector<glm::vec3>& x, std::vector<glm::vec3>& y) {
                           y.assign(x.size(), glm::vec3(0.0f));
                         })
        .first_hit;
  };
  for (std::size_t l = 0; l < lights.size(); ++l)
    with_polygons.push_back(relative_difference(first_hit(lights[l]), b.probe.first_hit[l]));
  // The same bake without its polygons falls back to the samples' points.
  b.samples.carried.clear();
  b.samples.carried_first.clear();
  b.samples.carried_vertices.clear();
  for (std::size_t l = 0; l < lights.size(); ++l)
    at_samples.push_back(relative_difference(first_hit(lights[l]), b.probe.first_hit[l]));
  for (std::size_t l = 0; l < lights.size(); ++l)
    EXPECT_LT(with_polygons[l], 1e-5) << "light " << l;
  // Without the files the test could not tell: the point evaluation must be
  // visibly different for the light under the ceiling.
  EXPECT_GT(at_samples[0], 1e-2);
}

TEST_F(CarriedPolygons, PolygonNamingAMissingSampleIsOneErrorNamingTheFile) {
  const auto polygons = read_npy_u32(out / "carried_polygons.npy");
  const auto samples = read_npy_f32(out / "samples.npy").shape[0];
  std::vector<std::uint32_t> bad = polygons.data;
  bad[polygons.shape[1] * (polygons.shape[0] - 1)] = static_cast<std::uint32_t>(samples);
  write_npy(out / "carried_polygons.npy", std::span<const std::uint32_t>(bad), polygons.shape);
  try {
    BakeReader::read(out);
    FAIL() << "a polygon of sample " << samples << " of " << samples << " was read";
  } catch (const BakeReader::ReadError& e) {
    EXPECT_NE(std::string(e.what()).find("carried_polygons.npy"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("names sample"), std::string::npos) << e.what();
  }
}

TEST_F(CarriedPolygons, PolygonWithTooFewVerticesIsRejected) {
  const auto polygons = read_npy_u32(out / "carried_polygons.npy");
  std::vector<std::uint32_t> bad = polygons.data;
  bad[2] = 2;  // polygon 0: two corners
  write_npy(out / "carried_polygons.npy", std::span<const std::uint32_t>(bad), polygons.shape);
  EXPECT_THROW(BakeReader::read(out), BakeReader::ReadError);
}

TEST_F(CarriedPolygons, PolygonsNameTheirTriangleAndSide) {
  // Each polygon lies in the plane of the triangle it names (its corners
  // within rounding of that plane), on a side the triangle has.
  const auto polygons = read_npy_u32(out / "carried_polygons.npy");
  ASSERT_EQ(polygons.shape[1], 5u);
  const auto vertices = read_npy_f32(out / "carried_vertices.npy");
  Diagnostics d;
  const Scene loaded = SceneLoader(d).load(scene("cornell-box"));
  const float size = glm::length(loaded.bounds().hi - loaded.bounds().lo);
  std::size_t back = 0;
  for (std::size_t r = 0; r < polygons.shape[0]; ++r) {
    const std::uint32_t* row = &polygons.data[5 * r];
    const std::uint32_t t = row[3];
    ASSERT_LT(t, loaded.triangle_count()) << "polygon " << r;
    ASSERT_LE(row[4], 1u) << "polygon " << r;
    back += row[4];
    const glm::vec3 n = glm::normalize(loaded.triangle_cross(t)), a = loaded.vertex(t, 0);
    for (std::uint32_t k = 0; k < row[2]; ++k) {
      const float* v = &vertices.data[3 * (row[1] + k)];
      ASSERT_LT(std::abs(glm::dot(glm::vec3(v[0], v[1], v[2]) - a, n)), 1e-5f * size)
          << "polygon " << r << " corner " << k << " is off triangle " << t;
    }
  }
  // The Cornell box's triangles are one-sided: no back side is carried.
  EXPECT_EQ(back, 0u);
}

}  // namespace
}  // namespace bounce::itest
