// Direct light of a point light integrated over the polygons each sample
// carries: a planar polygon facing the light receives intensity x the solid
// angle it subtends, exactly, so the patches of a square under a point light
// must add up to the square's analytic solid angle however the samples fall.
//
// With the light at h = 0.05 a above the square, 2 pi (1 - h / sqrt(h^2 +
// 0.01 a^2)) = 3.47 of the square's 5.72 sr lie within 0.1 a of the axis,
// where a point evaluation (cos / r^2 at the sample, times its area; the
// runtime did that before) sees only the few samples that fall there. The
// test measures that estimate too and requires it to miss by 50x the
// tolerance (with this bake's samples it misses by 11% on the axis and 40%
// above a corner), so the exact sum is not passing by luck of the layout.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "bake/bake.h"
#include "runtime/direct_light.h"
#include "test_scenes.h"

namespace bounce {

namespace {

struct SceneBake {
  Scene scene;
  BakeResult bake;
};

SceneBake bake_scene(Scene scene, int voxels = 4) {
  SceneBake s{std::move(scene), {}};
  BakeSettings settings;
  settings.voxel_resolution = voxels;
  settings.patch_mode = PatchMode::Virtual;
  settings.codec = CodecChoice::Dense;
  settings.pictures = false;
  Diagnostics d;
  Progress p;
  s.bake = Baker(s.scene, settings, d).run(p);
  return s;
}

// Unit squares at z = 0 (mesh 0, facing +z) and z = 1.
const SceneBake& parallel_squares() {
  static const SceneBake b = bake_scene(test_scenes::parallel_squares());
  return b;
}

// A unit floor at y = 0 (mesh 0, facing +y) and a wall at z = 0 (facing +z).
const SceneBake& perpendicular_squares() {
  static const SceneBake b = bake_scene(test_scenes::perpendicular_squares());
  return b;
}

// The parallel squares with a two-sided occluder at z = 0.1 over x in
// [0.55, 1.15], y in [-0.5, 1.5]: from a light at (0.5, 0.5, 0.2) it shades
// the bottom square exactly where x > 0.6 (its edge projects from the light
// with a factor 2).
const SceneBake& half_shaded_square() {
  static const SceneBake b = [] {
    Scene s = test_scenes::parallel_squares();
    test_scenes::add_mesh(
        s, "occluder",
        {{0.55f, -0.5f, 0.1f}, {1.15f, -0.5f, 0.1f}, {1.15f, 1.5f, 0.1f}, {0.55f, 1.5f, 0.1f}},
        {{0, 1, 2}, {0, 2, 3}}, glm::vec3(0.5f), glm::vec3(0.0f), true);
    return bake_scene(std::move(s), 8);
  }();
  return b;
}

struct Received {
  double exact_sum = 0.0;  // sum over the mesh's patches of E x area
  double point_sum = 0.0;  // the same from point evaluations at the samples
  double area = 0.0;
};

// What mesh 0 of a bake receives from one point light.
Received first_mesh_power(const SceneBake& b, const Light& light) {
  const RayTracer tracer(b.scene);
  const std::vector<glm::vec3> e =
      direct_irradiance(tracer, b.bake.samples, b.bake.patches, {light});
  Received r;
  for (std::size_t p = 0; p < b.bake.patches.size(); ++p) {
    if (b.bake.patches.patches[p].mesh != 0) continue;
    for (std::uint32_t k = b.bake.patches.member_first[p]; k < b.bake.patches.member_first[p + 1];
         ++k) {
      const Sample& s = b.bake.samples.samples[b.bake.patches.member_samples[k]];
      r.exact_sum += static_cast<double>(s.area) * e[p].r;
      r.point_sum +=
          static_cast<double>(s.area) * irradiance_at(tracer, s.position, s.normal, {light}).r;
      r.area += s.area;
    }
  }
  return r;
}

Light point_light(glm::vec3 position, float intensity) {
  Light l;
  l.type = Light::Type::Point;
  l.position = position;
  l.intensity = intensity;
  return l;
}

// The a x a square's average irradiance from the polygons must be I x omega
// / a^2 within 1e-3; where the light is close (`point_far_off`), the point
// evaluation on the same samples must miss by more than 5%, or the test
// proves nothing.
void expect_solid_angle(const Received& r, double a, double intensity, double omega,
                        bool point_far_off) {
  const double expected = intensity * omega / (a * a);
  EXPECT_NEAR(r.exact_sum / r.area / expected, 1.0, 1e-3);
  if (point_far_off) {
    EXPECT_GT(std::abs(r.point_sum / r.area / expected - 1.0), 0.05)
        << "the point evaluation should be far off here, or the test proves nothing";
  }
}

}  // namespace

TEST(DirectLightPolygons, SquareUnderAPointLightOnItsAxisGetsItsSolidAngle) {
  const double a = 1.0, h = 0.05 * a, intensity = 2.0;
  const Received r = first_mesh_power(
      parallel_squares(),
      point_light(glm::vec3(0.5f, 0.5f, static_cast<float>(h)), static_cast<float>(intensity)));
  ASSERT_NEAR(r.area, a * a, 1e-4) << "the samples must carry the whole square";
  expect_solid_angle(r, a, intensity, 4.0 * std::asin(a * a / (a * a + 4.0 * h * h)), true);
}

TEST(DirectLightPolygons, SquareUnderAPointLightAboveACornerGetsItsSolidAngle) {
  // Off the axis, so the polygons' solid angles are asymmetric: a light at
  // height h above a corner of an a x a square sees atan(a^2 / (h sqrt(2 a^2 + h^2))).
  const double a = 1.0, h = 0.05 * a, intensity = 1.0;
  const Received r = first_mesh_power(
      parallel_squares(),
      point_light(glm::vec3(0.0f, 0.0f, static_cast<float>(h)), static_cast<float>(intensity)));
  expect_solid_angle(r, a, intensity, std::atan(a * a / (h * std::sqrt(2.0 * a * a + h * h))),
                     true);
}

TEST(DirectLightPolygons, SquareUnderAFarPointLightGetsItsSolidAngle) {
  // At h = 3 a every polygon is small against its distance from the light and
  // takes the midpoint rule (area x cos / r^2 at its centroid) instead of the
  // exact solid angle; its error, of order (size / distance)^2, must stay
  // within the same tolerance. (The wall at z = 0 does not shade the floor.)
  const double a = 1.0, h = 3.0 * a, intensity = 1.0;
  const Received r = first_mesh_power(
      perpendicular_squares(),
      point_light(glm::vec3(0.5f, static_cast<float>(h), 0.5f), static_cast<float>(intensity)));
  ASSERT_NEAR(r.area, a * a, 1e-4) << "the samples must carry the whole floor";
  expect_solid_angle(r, a, intensity, 4.0 * std::asin(a * a / (a * a + 4.0 * h * h)), false);
}

TEST(DirectLightPolygons, ShadowIsJudgedAtPointsInsideEachPolygon) {
  // Visibility is judged per polygon (by its own shadow rays, or its
  // sample's), at points inside the polygon or at the sample: a sample whose
  // polygons lie wholly on the lit side of the shadow edge x = 0.6 must get
  // what it gets with the occluder removed, one wholly on the shaded side
  // nothing, and one across the edge something in between. Each sample is
  // its own patch here, so the direct light comes back per sample.
  const SceneBake& b = half_shaded_square();
  const SampleSet& set = b.bake.samples;
  PatchSet per_sample;
  per_sample.patches.resize(set.samples.size());
  per_sample.member_first.push_back(0);
  for (std::uint32_t k = 0; k < set.samples.size(); ++k) {
    per_sample.member_samples.push_back(k);
    per_sample.member_first.push_back(k + 1);
  }
  // The same squares without the occluder (appended last, so the squares'
  // triangles keep their indices).
  const RayTracer shaded(b.scene), open(test_scenes::parallel_squares());
  const Light light = point_light(glm::vec3(0.5f, 0.5f, 0.2f), 1.0f);
  const std::vector<glm::vec3> e_shaded = direct_irradiance(shaded, set, per_sample, {light});
  const std::vector<glm::vec3> e_open = direct_irradiance(open, set, per_sample, {light});
  const float edge = 0.6f, margin = 1e-3f;
  int lit = 0, dark = 0, across = 0;
  for (std::size_t k = 0; k < set.samples.size(); ++k) {
    const Sample& s = set.samples[k];
    if (s.mesh != 0) continue;
    float lo = s.position.x, hi = s.position.x;
    for (std::uint32_t c = set.carried_first[k]; c < set.carried_first[k + 1]; ++c) {
      const CarriedArea& piece = set.carried[c];
      for (std::uint32_t i = 0; i < piece.vertex_count; ++i) {
        lo = std::min(lo, set.carried_vertices[piece.first_vertex + i].x);
        hi = std::max(hi, set.carried_vertices[piece.first_vertex + i].x);
      }
    }
    ASSERT_GT(e_open[k].r, 0.0f) << "sample " << k << " faces the light unshaded";
    if (hi < edge - margin) {
      EXPECT_EQ(e_shaded[k].r, e_open[k].r) << "lit sample " << k;
      ++lit;
    } else if (lo > edge + margin) {
      EXPECT_EQ(e_shaded[k].r, 0.0f) << "shaded sample " << k;
      ++dark;
    } else {
      EXPECT_GE(e_shaded[k].r, 0.0f);
      EXPECT_LE(e_shaded[k].r, e_open[k].r);
      ++across;
    }
  }
  EXPECT_GT(lit, 10);
  EXPECT_GT(dark, 10);
}

TEST(DirectLightPolygons, SquareFacingAwayFromThePointLightGetsNothing) {
  // The bottom square faces +z; a light below it sees its back.
  const Received r =
      first_mesh_power(parallel_squares(), point_light(glm::vec3(0.5f, 0.5f, -0.05f), 1.0f));
  EXPECT_EQ(r.exact_sum, 0.0);
}

TEST(DirectLightPolygons, PolygonFramesMatchTheirGeometry) {
  // One sample carrying an L-shaped hexagon in the plane z = 2, wound
  // clockwise seen from +z (its fan normal is -z), the sample facing +z: the
  // frame must face the sample's side, and its area, centroid and radius are
  // those of the L (a 2 x 2 square less its 1 x 1 top-right quarter: area 3,
  // centroid (5/6, 5/6), farthest vertex (2, 0) or (0, 2)). A two-vertex
  // polygon is degenerate (area 0).
  SampleSet set;
  Sample s{};
  s.normal = glm::vec3(0.0f, 0.0f, 1.0f);
  set.samples = {s};
  const std::vector<glm::vec3> l_shape = {{0, 0, 2}, {0, 2, 2}, {1, 2, 2},
                                          {1, 1, 2}, {2, 1, 2}, {2, 0, 2}};
  set.carried_vertices = l_shape;
  set.carried_vertices.push_back({5, 5, 5});
  set.carried_vertices.push_back({6, 5, 5});
  set.carried.push_back(CarriedArea{0, false, 3.0f, 0, 6, false, 0});
  set.carried.push_back(CarriedArea{0, false, 0.0f, 6, 2, false, 0});
  set.carried_first = {0, 2};
  const std::vector<CarriedPolygonFrame> frames = carried_polygon_frames(set);
  ASSERT_EQ(frames.size(), 2u);
  const CarriedPolygonFrame& f = frames[0];
  EXPECT_NEAR(f.area, 3.0f, 1e-6f);
  EXPECT_NEAR(f.normal.z, 1.0f, 1e-6f);
  EXPECT_NEAR(f.centroid.x, 5.0f / 6.0f, 1e-6f);
  EXPECT_NEAR(f.centroid.y, 5.0f / 6.0f, 1e-6f);
  EXPECT_NEAR(f.centroid.z, 2.0f, 1e-6f);
  const float far = (2.0f - 5.0f / 6.0f) * (2.0f - 5.0f / 6.0f) + (5.0f / 6.0f) * (5.0f / 6.0f);
  EXPECT_NEAR(f.radius2, far, 1e-5f);
  EXPECT_EQ(frames[1].area, 0.0f);
  // Samples without polygons (an older bake folder) have no frames.
  set.carried_first.clear();
  EXPECT_TRUE(carried_polygon_frames(set).empty());
}

TEST(DirectLightPolygons, FramesComputedOnceGiveTheSameLight) {
  // The runtime computes the frames once per sample set and passes them in;
  // the result must be the per-call computation's, bit for bit (the same
  // sums in the same order), and a frame table of the wrong size an error.
  const SceneBake& b = perpendicular_squares();
  const RayTracer tracer(b.scene);
  const std::vector<Light> lights = {point_light(glm::vec3(0.3f, 0.4f, 0.6f), 2.0f)};
  const std::vector<glm::vec3> per_call =
      direct_irradiance(tracer, b.bake.samples, b.bake.patches, lights);
  const std::vector<CarriedPolygonFrame> frames = carried_polygon_frames(b.bake.samples);
  ASSERT_EQ(frames.size(), b.bake.samples.carried.size());
  std::vector<glm::vec3> once(b.bake.patches.size());
  direct_irradiance(tracer, b.bake.samples, frames, b.bake.patches, lights, {}, 4, once);
  float total = 0.0f;
  for (std::size_t p = 0; p < once.size(); ++p) {
    EXPECT_EQ(once[p], per_call[p]) << "patch " << p;
    total += once[p].r;
  }
  EXPECT_GT(total, 0.0f);
  const std::span<const CarriedPolygonFrame> short_table(frames.data(), frames.size() - 1);
  EXPECT_THROW(
      direct_irradiance(tracer, b.bake.samples, short_table, b.bake.patches, lights, {}, 4, once),
      Error);
}

}  // namespace bounce
