// Final gather (runtime/final_gather.h): point-to-patch form factors by rays,
// held against the exact point-to-polygon form factor and against the
// path-traced reference in a concave corner; and its per-frame work: the
// compact rows give the product of the float rows, and near sources lit in
// batches get the light irradiance_at() gives each alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "bake/bake.h"
#include "base/form_factor_kernel.h"
#include "base/random.h"
#include "patches/surface_patch_lookup.h"
#include "raytrace/ray_tracer.h"
#include "reference/path_tracer.h"
#include "runtime/direct_light.h"
#include "runtime/final_gather.h"
#include "runtime/final_gather_build.h"
#include "runtime/gather_row_loops.h"
#include "runtime/mesh_transfer.h"
#include "test_scenes.h"

namespace bounce {
namespace {

BakeResult bake_of(const Scene& scene, int voxel) {
  BakeSettings s;
  s.voxel_resolution = voxel;
  s.codec = CodecChoice::Dense;
  s.transport.backend = TransportSettings::Backend::OpenBLAS;
  s.pictures = false;
  Diagnostics d;
  Progress progress;
  return Baker(scene, s, d).run(progress);
}

// A bake's first-hit light under the scene's lights: b per patch and each
// sample's direct irradiance, as a frame computes them.
struct FirstHit {
  std::vector<glm::vec3> b, sample_irradiance;
};
FirstHit first_hit_of(const RayTracer& tracer, const BakeResult& bake, const Scene& scene) {
  std::vector<glm::vec3> irradiance(bake.patches.size());
  FirstHit f;
  f.sample_irradiance.resize(bake.samples.samples.size());
  direct_irradiance(tracer, bake.samples, bake.patches, scene.lights, {}, 4, irradiance,
                    f.sample_irradiance);
  f.b = first_bounce(bake.patches, irradiance);
  return f;
}

// What gather `g` gives its points from the first bounce alone (no T b):
// patches and clusters from b, samples and near sources from their own.
std::vector<glm::vec3> gathered_first_bounce(const FinalGather& g, const FirstHit& f,
                                             const BakeResult& bake, const RayTracer& tracer,
                                             const Scene& scene) {
  const std::vector<glm::vec3> no_indirect(f.b.size(), glm::vec3(0.0f));
  std::vector<glm::vec3> e;
  g.irradiance(f.b, sample_exitance(bake.samples, bake.patches, f.sample_irradiance, no_indirect),
               near_exitance(g.near, &tracer, scene.lights, {}, no_indirect), e);
  return e;
}

// A floor (y = 0, x and z in [-1, 1]) with a board at y = 0.5 over its
// half x < 0, and a wall at the floor's far edge (x = 1), so that patches see
// each other and stand where rays from above the floor would leave past it.
Scene floor_under_a_board() {
  Scene scene;
  test_scenes::add_quad(scene, "floor", {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});
  test_scenes::add_quad(scene, "board", {-1.5f, 0.5f, -1.5f}, {-1.5f, 0.5f, 1.5f}, {0, 0.5f, 1.5f},
                        {0, 0.5f, -1.5f});
  test_scenes::add_quad(scene, "wall", {1, 0, -1}, {1, 0, 1}, {1, 0.5f, 1}, {1, 0.5f, -1});
  return scene;
}

// A floor (y = 0) and a wall (z = 0) meeting at a right angle, the wall lit
// evenly by a directional light grazing the floor.
Scene corner_lit_along_the_floor() {
  Scene scene = test_scenes::perpendicular_squares();
  scene.lights.push_back({Light::Type::Directional, "sun", glm::vec3(0.0f),
                          glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(1.0f), 1.0f});
  return scene;
}

TEST(FinalGather, WeightsFacingALargeSquareSumToItsExactFormFactor) {
  const Scene scene = test_scenes::parallel_squares();
  const BakeResult bake = bake_of(scene, 4);
  const RayTracer tracer(scene);
  const SurfacePatchLookup lookup(bake.voxels, bake.samples, bake.patch_of_sample);
  const std::vector<glm::vec3> points = {
      {0.5f, 0.5f, 0.0f}, {0.1f, 0.2f, 0.0f}, {0.9f, 0.9f, 0.0f}};
  const std::vector<glm::vec3> normals(points.size(), glm::vec3(0, 0, 1));
  FinalGatherSettings fs;
  fs.rays = 4096;
  const FinalGather g = build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid,
                                           points, normals, fs);
  g.validate("gather");
  const glm::vec3 top[4] = {{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}};
  for (std::size_t i = 0; i < points.size(); ++i) {
    double sum = 0.0;
    for (std::uint64_t k = g.first[i]; k < g.first[i + 1]; ++k) {
      sum += g.weight[k];
      // Every ray lands on the top square, facing down.
      if (g.source[k] < g.patches) {
        EXPECT_LT(bake.patches.patches[g.source[k]].normal.z, -0.9f);
      } else if (g.source[k] >= g.patches + g.clusters) {
        EXPECT_LT(bake.samples.samples[g.source[k] - g.patches - g.clusters].normal.z, -0.9f);
      }
    }
    const double exact = point_to_polygon_form_factor(points[i], normals[i], top, 4);
    // Binomial standard error of 4096 independent rays; the stratified
    // pattern does better, so 3 of them is a bound that still fails on a
    // wrong weight (the point at the centre sees 0.24, at a corner 0.14).
    const double sigma = std::sqrt(exact * (1.0 - exact) / fs.rays);
    std::printf("final gather: point %zu sums to %.5f, exact %.5f (sigma %.4f)\n", i, sum, exact,
                sigma);
    EXPECT_NEAR(sum, exact, 3.0 * sigma);
  }
}

// The form factor from a point at height h above a plane, facing it, to a
// rectangle a x b of the plane with one corner under the point.
double corner_form_factor(double a, double b, double h) {
  const double x = a / h, y = b / h;
  return (x / std::sqrt(1.0 + x * x) * std::atan(y / std::sqrt(1.0 + x * x)) +
          y / std::sqrt(1.0 + y * y) * std::atan(x / std::sqrt(1.0 + y * y))) /
         (2.0 * std::numbers::pi);
}

TEST(FinalGather, NearSourcesFollowAShadowEdgeUnderThePoint) {
  // A floor (y = 0, x and z in [-1, 1]) under a sun straight above, its
  // half x < 0 shaded by a board at y = 0.5. Points 5 cm above the floor,
  // facing it, across the shadow's edge: each sees the lit half with the
  // analytic form factor of a rectangle, and nothing else reflects (the
  // board's underside is a one-sided back face), so its indirect irradiance
  // is albedo x sun x F (a wall at the far edge gets no sun). A sample stands for ~9 cm of floor
  // and is lit at its centre: every point across the edge would read the same few samples.
  Scene scene = floor_under_a_board();
  scene.lights.push_back({Light::Type::Directional, "sun", glm::vec3(0.0f),
                          glm::vec3(0.0f, -1.0f, 0.0f), glm::vec3(1.0f), 1.0f});
  const BakeResult bake = bake_of(scene, 8);
  const RayTracer tracer(scene);
  const SurfacePatchLookup lookup(bake.voxels, bake.samples, bake.patch_of_sample);
  const FirstHit first_hit = first_hit_of(tracer, bake, scene);
  const double h = 0.05, albedo = 0.5;
  const std::vector<double> offsets = {-0.06, -0.03, 0.0, 0.03, 0.06};
  std::vector<glm::vec3> points, normals;
  for (double d : offsets) {
    points.emplace_back(static_cast<float>(d), static_cast<float>(h), 0.0f);
    normals.emplace_back(0.0f, -1.0f, 0.0f);
  }
  FinalGatherSettings with_near;
  with_near.rays = 4096;
  with_near.near = 1.0f;           // every ray within a voxel
  with_near.near_resolution = 96;  // 4 mm cells: the edge blurs over one
  // Every cell kept, even one ray's: this is about the cells themselves
  // (4 mm cells take one or two of a point's rays each).
  with_near.near_min_rays = 1;
  // The samples at their centres: no near sources, no spots.
  FinalGatherSettings without_near = with_near;
  without_near.near = 0.0f;
  without_near.spots = 0;
  const auto gathered = [&](const FinalGatherSettings& fs) {
    const FinalGather g = build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid,
                                             points, normals, fs);
    g.validate("shadow edge");
    return std::make_pair(gathered_first_bounce(g, first_hit, bake, tracer, scene), g.near.size());
  };
  const auto [near_e, near_count] = gathered(with_near);
  const auto [far_e, far_count] = gathered(without_near);
  EXPECT_GT(near_count, 100u);
  EXPECT_EQ(far_count, 0u);
  double near_error = 0.0, sample_error = 0.0;
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    const double d = offsets[i];
    // Lit: x in [0, 1], z in [-1, 1], split at the point's foot x = d.
    const double f = 2.0 * corner_form_factor(1.0 - d, 1.0, h) +
                     (d >= 0.0 ? 1.0 : -1.0) * 2.0 * corner_form_factor(std::abs(d), 1.0, h);
    const double exact = albedo * f;
    // Bound: three standard deviations of the rays' binomial estimate of f,
    // plus a 4 mm band of the floor at the edge read wrong (the form factor
    // per metre across the edge is at most 1 / (pi h)).
    const double sigma = albedo * std::sqrt(f * (1.0 - f) / with_near.rays);
    const double band = albedo * 0.004 / (std::numbers::pi * h);
    std::printf("shadow edge at %+.2f m: exact %.4f, near sources %.4f, samples only %.4f\n", d,
                exact, near_e[i].r, far_e[i].r);
    EXPECT_NEAR(near_e[i].r, exact, 3.0 * sigma + band) << d;
    near_error += std::abs(near_e[i].r - exact);
    sample_error += std::abs(far_e[i].r - exact);
  }
  EXPECT_LT(near_error, 0.5 * sample_error);
}

Scene shaded_floor();  // below

TEST(FinalGather, SpotsLieWhereTheirSamplesRaysLanded) {
  // Points 40 cm over the shaded floor: each sample's spots are at most
  // `spots`, the ones most rays landed on first, on the sample's surface
  // (within a voxel of its centre, the side it faces), lit with its albedo
  // and carrying its patch's T b; no row reads them.
  const Scene scene = shaded_floor();
  const BakeResult bake = bake_of(scene, 8);
  const RayTracer tracer(scene);
  const SurfacePatchLookup lookup(bake.voxels, bake.samples, bake.patch_of_sample);
  std::vector<glm::vec3> points, normals;
  for (int i = 0; i < 40; ++i) {
    const float t = static_cast<float>(i) / 39.0f;
    points.emplace_back(-0.9f + 1.8f * t, 0.4f, 0.5f - t);
    normals.emplace_back(0.0f, -1.0f, 0.0f);
  }
  FinalGatherSettings fs;
  const FinalGather g = build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid,
                                           points, normals, fs);
  g.validate("spots");
  ASSERT_EQ(g.spot_first.size(), bake.samples.samples.size() + 1);
  ASSERT_GT(g.spots(), 50u);
  const float voxel = bake.voxels.grid.cell_size();
  for (std::size_t s = 0; s < bake.samples.samples.size(); ++s) {
    const Sample& sample = bake.samples.samples[s];
    ASSERT_LE(g.spot_first[s + 1] - g.spot_first[s], static_cast<std::uint32_t>(fs.spots));
    for (std::uint32_t k = g.spot_first[s]; k < g.spot_first[s + 1]; ++k) {
      const std::size_t n = g.spot_base() + k;
      if (k > g.spot_first[s]) {
        EXPECT_LE(g.spot_weight[k], g.spot_weight[k - 1]) << s;
      }
      EXPECT_EQ(g.near.patch[n], static_cast<std::uint32_t>(bake.patch_of_sample[s])) << s;
      EXPECT_EQ(g.near.albedo[n], sample.albedo) << s;
      EXPECT_LE(glm::distance(g.near.position[n], sample.position), voxel) << s;
      EXPECT_GT(glm::dot(g.near.normal[n], sample.normal), 0.5f) << s;
    }
  }
  for (const std::uint32_t src : g.source)
    EXPECT_LT(src, g.patches + g.clusters + g.samples + g.spot_base());
}

TEST(FinalGather, ASampleWithSpotsCarriesTheirLight) {
  // Two samples of one patch, the first with two spots: by hand, a sample
  // entry reads 0.25 x spot 0 + 0.75 x spot 1, a patch entry its seen
  // samples' light (spots included), a cluster its patch's.
  FinalGather g;
  g.patches = 1;
  g.clusters = 1;
  g.samples = 2;
  g.cluster_of_patch = {0};
  g.cluster_share = {1.0f};
  g.seen_first = {0, 2};
  g.seen_sample = {0, 1};
  g.seen_weight = {0.5f, 0.5f};
  for (int k = 0; k < 3; ++k) {  // one near source the rows read, two spots
    g.near.position.emplace_back(0.0f);
    g.near.normal.emplace_back(0.0f, 1.0f, 0.0f);
    g.near.albedo.emplace_back(0.5f);
    g.near.patch.push_back(0);
  }
  g.spot_first = {0, 2, 2};
  g.spot_weight = {0.25f, 0.75f};
  g.near.spot_count = 2;
  // Rows: sample 0, sample 1, the patch, the cluster, the near source.
  g.first = {0, 1, 2, 3, 4, 5};
  g.source = {2, 3, 0, 1, 4};
  g.weight = {1.0f, 1.0f, 0.5f, 1.0f, 1.0f};
  g.validate("by hand");
  const std::vector<glm::vec3> patch = {glm::vec3(100.0f)};                  // read by no row
  const std::vector<glm::vec3> sample = {glm::vec3(3.0f), glm::vec3(2.0f)};  // centres
  const std::vector<glm::vec3> near = {glm::vec3(9.0f), glm::vec3(4.0f), glm::vec3(8.0f)};
  std::vector<glm::vec3> e;
  g.irradiance(patch, sample, near, e);
  ASSERT_EQ(e.size(), 5u);
  const float spotted = 0.25f * 4.0f + 0.75f * 8.0f;  // 7, not the centre's 3
  EXPECT_FLOAT_EQ(e[0].x, spotted);
  EXPECT_FLOAT_EQ(e[1].x, 2.0f);
  EXPECT_FLOAT_EQ(e[2].x, 0.5f * (0.5f * spotted + 0.5f * 2.0f));
  EXPECT_FLOAT_EQ(e[3].x, 0.5f * spotted + 0.5f * 2.0f);
  EXPECT_FLOAT_EQ(e[4].x, 9.0f);
  // Spot weights that do not sum to 1 are one error.
  FinalGather bad = g;
  bad.spot_weight = {0.25f, 0.5f};
  EXPECT_THROW(bad.validate("by hand"), Error);
  bad = g;
  bad.spot_first = {0, 3, 3};
  EXPECT_THROW(bad.validate("by hand"), Error);
  bad = g;
  bad.near.spot_count = 1;  // the near sources and the row starts disagree
  EXPECT_THROW(bad.validate("by hand"), Error);
  // Row starts whose last value is right but one in between runs past the
  // entries: one error, before any entry beyond the end is read (a fuzzed
  // bake folder found this; under ASan a read past the end aborts).
  bad = g;
  bad.first = {0, 1, 9, 3, 4, 5};
  EXPECT_THROW(bad.validate("by hand"), Error);
  bad = g;
  bad.spot_first = {0, 4, 2};
  EXPECT_THROW(bad.validate("by hand"), Error);
}

TEST(FinalGather, NearSourcesLieOnTheFaceTheirRaysLandedOn) {
  // A moulding: a half-cylinder 3 cm across, 48 facets of 2 mm, lying on a
  // floor under a slanting sun. The facets are too small for the sampling
  // rays, so a sample carries its neighbours' facets up to 60 degrees away
  // from its own. A near-source cell spanning several facets would be lit
  // at the mean of their points, inside the moulding, with one facet's
  // normal: each source must lie on the surface, facing the way it faces
  // there, and the points beside the moulding must get the light a ray
  // reading its own hit point gives (a second, brute-force gather).
  Scene scene;
  test_scenes::add_quad(scene, "floor", {-0.5f, 0, -0.5f}, {-0.5f, 0, 0.5f}, {0.5f, 0, 0.5f},
                        {0.5f, 0, -0.5f});
  constexpr int kFacets = 48;
  constexpr float kRadius = 0.015f;
  std::vector<glm::vec3> v;
  std::vector<glm::uvec3> t;
  for (int k = 0; k <= kFacets; ++k) {
    const float a = std::numbers::pi_v<float> * static_cast<float>(k) / kFacets;
    v.emplace_back(kRadius * std::cos(a), kRadius * std::sin(a), -0.4f);
    v.emplace_back(kRadius * std::cos(a), kRadius * std::sin(a), 0.4f);
  }
  for (std::uint32_t k = 0; k < kFacets; ++k)
    t.push_back({2 * k, 2 * k + 2, 2 * k + 3}), t.push_back({2 * k, 2 * k + 3, 2 * k + 1});
  test_scenes::add_mesh(scene, "moulding", v, t);
  scene.lights.push_back({Light::Type::Directional, "sun", glm::vec3(0.0f),
                          glm::normalize(glm::vec3(-1.0f, -1.0f, 0.0f)), glm::vec3(1.0f), 1.0f});
  const BakeResult bake = bake_of(scene, 6);
  const RayTracer tracer(scene);
  const SurfacePatchLookup lookup(bake.voxels, bake.samples, bake.patch_of_sample);
  // Points on the floor on both sides of the moulding, facing up.
  std::vector<glm::vec3> points, normals;
  for (float x : {-0.04f, -0.025f, 0.025f, 0.04f})
    for (float z : {-0.1f, 0.0f, 0.1f}) {
      points.emplace_back(x, 0.0f, z);
      normals.emplace_back(0.0f, 1.0f, 0.0f);
    }
  FinalGatherSettings fs;
  fs.rays = 2048;
  fs.near = 1.0f;
  fs.near_min_rays = 1;  // every cell kept: this is about where the cells lie
  const FinalGather g = build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid,
                                           points, normals, fs);
  g.validate("moulding");
  ASSERT_GT(g.near.size(), 100u);
  // On the surface: a ray back along the normal from 5 mm out meets a face
  // 5 mm away (within the facets' sagitta, 0.05 mm) facing the same way.
  std::size_t off_surface = 0;
  for (std::size_t k = 0; k < g.near.size(); ++k) {
    const glm::vec3 n = g.near.normal[k];
    const Hit h = tracer.intersect(g.near.position[k] + 0.005f * n, -n);
    if (!h.hit || std::abs(h.t - 0.005f) > 1e-4f || glm::dot(h.geometric_normal, n) < 0.999f)
      ++off_surface;
  }
  EXPECT_EQ(off_surface, 0u) << "of " << g.near.size() << " near sources";
  // The light: the first bounce only, against every ray's own hit point.
  const std::vector<glm::vec3> e =
      gathered_first_bounce(g, first_hit_of(tracer, bake, scene), bake, tracer, scene);
  const float eps = fs.offset_epsilons * tracer.epsilon();
  const int rays = 8192;
  double gathered = 0.0, brute = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    double sum = 0.0;
    Rng rng(7, i);
    for (int k = 0; k < rays; ++k) {
      const float r = std::sqrt(rng.uniform()),
                  phi = 2.0f * std::numbers::pi_v<float> * rng.uniform();
      const glm::vec3 dir(r * std::cos(phi), std::sqrt(std::max(0.0f, 1.0f - r * r)),
                          r * std::sin(phi));
      glm::vec3 o = points[i] + eps * normals[i];
      const Hit h = intersect_leaving_surface(tracer, o, dir, eps);
      if (!h.hit || glm::dot(dir, h.geometric_normal) > 0.0f) continue;
      const glm::vec3 x = o + h.t * dir;
      sum += 0.5 * irradiance_at(tracer, x + eps * h.geometric_normal, h.geometric_normal,
                                 scene.lights, {}, 4, k)
                       .r;
    }
    gathered += e[i].r;
    brute += sum / rays;
  }
  std::printf("moulding: gathered first bounce %.5f, every ray at its hit point %.5f\n", gathered,
              brute);
  // Both are ray estimates of the same integral over 12 points (2048 and
  // 8192 rays each, most of the light from the floor's lit part): 3% covers
  // their noise several times over. Cells mixing facets, lit inside the
  // moulding, gave a quarter of it (0.048 against 0.184).
  EXPECT_NEAR(gathered, brute, 0.03 * brute);
}

// A floor (y = 0, x and z in [-1, 1]) under a sun straight above, and a
// block standing on it ([kBlockA, kBlockB] in x and z, 0.3 high, no bottom):
// the floor is lit everywhere but under the block. The floor's triangles run
// on under the block, their diagonal clear of the corner at (kBlockA,
// kBlockA), so one triangle holds the floor on both sides of that corner.
constexpr float kBlockA = 0.01f, kBlockB = 0.6f;
Scene block_on_a_floor() {
  Scene scene;
  test_scenes::add_quad(scene, "floor", {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1});
  const float a = kBlockA, b = kBlockB, top = 0.3f;
  test_scenes::add_quad(scene, "block -x", {a, 0, a}, {a, 0, b}, {a, top, b}, {a, top, a});
  test_scenes::add_quad(scene, "block -z", {a, 0, a}, {a, top, a}, {b, top, a}, {b, 0, a});
  test_scenes::add_quad(scene, "block +x", {b, 0, a}, {b, top, a}, {b, top, b}, {b, 0, b});
  test_scenes::add_quad(scene, "block +z", {a, 0, b}, {b, 0, b}, {b, top, b}, {a, top, b});
  test_scenes::add_quad(scene, "block top", {a, top, a}, {a, top, b}, {b, top, b}, {b, top, a});
  scene.lights.push_back({Light::Type::Directional, "sun", glm::vec3(0.0f),
                          glm::vec3(0.0f, -1.0f, 0.0f), glm::vec3(1.0f), 1.0f});
  return scene;
}

TEST(FinalGather, NearSourcesAtTheFootOfABlockLieInItsLight) {
  // Points 5 mm up the block's two faces at one corner send rays onto the
  // floor in front of one face and beside the other, into the same cells of
  // the same triangle and sample. A near source lit at the mean of those
  // landing points would lie under the block, in its shade. Every near
  // source lies where a ray landed, on lit floor: its light is the floor's
  // albedo x the sun's irradiance (1), and it lies outside the block's
  // footprint.
  const Scene scene = block_on_a_floor();
  const float a = kBlockA, b = kBlockB;
  const BakeResult bake = bake_of(scene, 4);
  const RayTracer tracer(scene);
  const SurfacePatchLookup lookup(bake.voxels, bake.samples, bake.patch_of_sample);
  std::vector<glm::vec3> points, normals;
  for (float t : {0.005f, 0.01f, 0.02f, 0.03f, 0.04f, 0.05f}) {
    points.emplace_back(a, 0.005f, a + t);
    normals.emplace_back(-1.0f, 0.0f, 0.0f);
    points.emplace_back(a + t, 0.005f, a);
    normals.emplace_back(0.0f, 0.0f, -1.0f);
  }
  FinalGatherSettings fs;
  fs.rays = 2048;
  fs.near = 1.0f;          // every ray within a voxel
  fs.near_resolution = 4;  // cells 12.5 cm across: one holds the corner
  fs.near_min_rays = 1;    // every cell kept: this is about where the cells lie
  fs.spots = 0;
  const FinalGather g = build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid,
                                           points, normals, fs);
  g.validate("block");
  const std::vector<glm::vec3> no_indirect(bake.patches.size(), glm::vec3(0.0f));
  const std::vector<glm::vec3> light =
      near_exitance(g.near, &tracer, scene.lights, {}, no_indirect);
  std::size_t on_floor = 0, under_block = 0, shaded = 0;
  for (std::size_t k = 0; k < g.near.size(); ++k) {
    if (g.near.normal[k].y < 0.999f) continue;  // the block's faces get no sun
    ++on_floor;
    const glm::vec3 x = g.near.position[k];
    if (x.x > a + 1e-4f && x.z > a + 1e-4f && x.x < b && x.z < b) ++under_block;
    if (std::abs(light[k].r - 0.5f) > 1e-5f) ++shaded;
  }
  std::printf("block: %zu near sources on the floor, %zu under the block, %zu shaded\n", on_floor,
              under_block, shaded);
  ASSERT_GT(on_floor, 10u);
  EXPECT_EQ(under_block, 0u);
  EXPECT_EQ(shaded, 0u);
}

TEST(FinalGather, PointsShutInsideTheGeometryGatherNothing) {
  // Points on the floor under the block, facing up, are shut inside it: all
  // of their rays meet the inside (the back) of its one-sided faces. They
  // are counted as enclosed and gather nothing; a point outside at the
  // block's foot, half of whose hemisphere is the block's lit-side floor,
  // is not.
  const Scene scene = block_on_a_floor();
  const BakeResult bake = bake_of(scene, 4);
  const RayTracer tracer(scene);
  const SurfacePatchLookup lookup(bake.voxels, bake.samples, bake.patch_of_sample);
  const std::vector<glm::vec3> points = {
      {0.3f, 0.0f, 0.3f}, {0.2f, 0.0f, 0.5f}, {kBlockA, 0.005f, 0.2f}};
  const std::vector<glm::vec3> normals = {{0, 1, 0}, {0, 1, 0}, {-1, 0, 0}};
  FinalGatherSettings fs;
  fs.rays = 256;
  const FinalGather g = build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid,
                                           points, normals, fs);
  g.validate("enclosed");
  EXPECT_EQ(g.points_enclosed, 2u);
  EXPECT_EQ(g.first[1] - g.first[0], 0u);
  EXPECT_EQ(g.first[2] - g.first[1], 0u);
  EXPECT_GT(g.first[3] - g.first[2], 0u);
  const std::vector<glm::vec3> e =
      gathered_first_bounce(g, first_hit_of(tracer, bake, scene), bake, tracer, scene);
  EXPECT_EQ(e[0], glm::vec3(0.0f));
  EXPECT_EQ(e[1], glm::vec3(0.0f));
  EXPECT_GT(e[2].r, 0.1f);  // about albedo x half the hemisphere's lit floor
}

TEST(FinalGather, ConcaveCornerGetsItsLightFromTheWallBesideIt) {
  // A floor and a wall meeting at a right angle, the wall lit evenly by a
  // directional light grazing the floor: a floor point next to the corner
  // sees half its hemisphere filled by the lit wall, far more than the
  // coarse patch it lies in does on average. The gather must give the
  // reference's indirect light there within its noise, and more than the
  // patch-constant value.
  const Scene scene = corner_lit_along_the_floor();
  const BakeResult bake = bake_of(scene, 3);
  const RayTracer tracer(scene);
  const glm::vec3 x(0.5f, 0.0f, 0.02f), n(0.0f, 1.0f, 0.0f);

  // Patch light after at least one reflection: b + T b; the samples' own.
  const FirstHit first_hit = first_hit_of(tracer, bake, scene);
  const std::vector<glm::vec3>& b = first_hit.b;
  const std::size_t np = bake.patches.size();
  const auto& t = bake.transport.channels[0].t;
  std::vector<glm::vec3> reflected(np), indirect(np);
  for (std::size_t p = 0; p < np; ++p) {
    glm::vec3 tb(0.0f);
    for (std::size_t q = 0; q < np; ++q) tb += t[p * np + q] * b[q];
    reflected[p] = b[p] + tb;
    indirect[p] = tb;
  }
  const SurfacePatchLookup lookup(bake.voxels, bake.samples, bake.patch_of_sample);
  FinalGatherSettings fs;
  fs.rays = 4096;
  const FinalGather g =
      build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid, {x}, {n}, fs);
  std::vector<glm::vec3> e;
  g.irradiance(reflected,
               sample_exitance(bake.samples, bake.patches, first_hit.sample_irradiance, indirect),
               near_exitance(g.near, &tracer, scene.lights, {}, indirect), e);
  const double gathered = e[0].r;

  // The patch the point lies in: its own indirect irradiance, (T b) / albedo.
  const std::int32_t own = lookup.patch_at(
      static_cast<std::uint32_t>(tracer.intersect(x + glm::vec3(0, 0.1f, 0), -n).triangle), false,
      x);
  ASSERT_GE(own, 0);
  double tb_own = 0.0;
  for (std::size_t q = 0; q < np; ++q) tb_own += t[static_cast<std::size_t>(own) * np + q] * b[q].r;
  const double patch_constant =
      tb_own / bake.patches.patches[static_cast<std::size_t>(own)].albedo.r;

  ReferenceSettings rs;
  rs.samples = 20000;
  const ReferencePathTracer pt(tracer, rs);
  const PointReference ref = pt.estimate_points({{x, n, glm::vec3(0.5f), glm::vec3(0.0f)}});
  const double reference = ref.indirect_irradiance[0].r;
  const double sigma = std::sqrt(ref.indirect_variance[0].r);
  std::printf("corner: gathered %.5f, patch-constant %.5f, reference %.5f +- %.5f\n", gathered,
              patch_constant, reference, sigma);
  EXPECT_GT(gathered, patch_constant);
  EXPECT_LT(std::abs(gathered - reference), 0.5 * std::abs(patch_constant - reference));
  // The reference's noise plus the bake's own (patch light is constant over
  // each patch of a 3-voxel grid; the gather's rays are stratified): 10%.
  EXPECT_NEAR(gathered, reference, 4.0 * sigma + 0.1 * reference);
}

TEST(FinalGather, SampleSourcesSplitThePatchesRaysAndKeepTheirLight) {
  // The same rays with and without sample sources: each point's total is
  // the same, and when every sample carries its own patch's light the two
  // gathers give the same irradiance (the sample entries only move rays
  // from a patch to its samples).
  const Scene scene = corner_lit_along_the_floor();
  const BakeResult bake = bake_of(scene, 3);
  const RayTracer tracer(scene);
  const SurfacePatchLookup lookup(bake.voxels, bake.samples, bake.patch_of_sample);
  std::vector<glm::vec3> points, normals;
  for (int i = 0; i < 5; ++i) {
    points.emplace_back(0.1f + 0.2f * static_cast<float>(i), 0.0f, 0.05f);
    normals.emplace_back(0.0f, 1.0f, 0.0f);
  }
  // Every patch kept exactly (no cluster remainder, whose membership would
  // differ between the two), so that only the sample entries differ.
  FinalGatherSettings with_samples;
  ASSERT_GT(with_samples.sample_kept, 0);
  with_samples.near = 0.0f;  // sample sources alone, lit at their centres
  with_samples.spots = 0;
  with_samples.kept = 100000;
  with_samples.coverage = 1.0;
  FinalGatherSettings patches_only = with_samples;
  patches_only.sample_kept = 0;
  const FinalGather a = build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid,
                                           points, normals, patches_only);
  const FinalGather b = build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid,
                                           points, normals, with_samples);
  a.validate("patches only");
  b.validate("with samples");
  EXPECT_EQ(a.samples, 0u);
  EXPECT_EQ(b.samples, bake.samples.samples.size());
  std::size_t sample_entries = 0;
  for (std::uint32_t src : b.source) sample_entries += src >= b.patches + b.clusters ? 1 : 0;
  EXPECT_GT(sample_entries, 0u);
  // Patch light: a ramp over the patches, so that a misplaced ray shows.
  std::vector<glm::vec3> patch_light(bake.patches.size()),
      sample_light(bake.samples.samples.size());
  for (std::size_t p = 0; p < patch_light.size(); ++p)
    patch_light[p] = glm::vec3(1.0f + static_cast<float>(p), 1.0f, 0.5f);
  for (std::size_t p = 0; p < patch_light.size(); ++p)
    for (std::uint32_t k = bake.patches.member_first[p]; k < bake.patches.member_first[p + 1]; ++k)
      sample_light[bake.patches.member_samples[k]] = patch_light[p];
  std::vector<glm::vec3> ea, eb;
  a.irradiance(patch_light, ea);
  b.irradiance(patch_light, sample_light, eb);
  EXPECT_THROW(b.irradiance(patch_light, ea), Error);  // sample sources need sample light
  for (std::size_t i = 0; i < points.size(); ++i) {
    double ta = 0.0, tb = 0.0;
    for (std::uint64_t k = a.first[i]; k < a.first[i + 1]; ++k) ta += a.weight[k];
    for (std::uint64_t k = b.first[i]; k < b.first[i + 1]; ++k) tb += b.weight[k];
    EXPECT_NEAR(ta, tb, 1e-5) << i;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(ea[i][c], eb[i][c], 1e-5 * (1.0 + ea[i][c])) << i;
  }
}

TEST(FinalGather, PatchEntriesCarryTheLightOfTheSamplesTheirRaysLandedOn) {
  // A patch entry reads its samples' light weighted by where the rays read
  // through patch entries landed, over all points. Summed over the points,
  // the gather then gives what a gather keeping every sample as its own
  // entry gives (the same rays), whatever the light of each sample; the
  // area mean would not.
  const Scene scene = corner_lit_along_the_floor();
  const BakeResult bake = bake_of(scene, 3);
  const RayTracer tracer(scene);
  const SurfacePatchLookup lookup(bake.voxels, bake.samples, bake.patch_of_sample);
  std::vector<glm::vec3> points, normals;
  for (int i = 0; i < 24; ++i) {
    const float t = static_cast<float>(i) / 23.0f;
    points.emplace_back(0.05f + 0.9f * t, 0.0f, 0.05f + 0.6f * t * t);
    normals.emplace_back(0.0f, 1.0f, 0.0f);
    points.emplace_back(0.0f, 0.05f + 0.9f * t, 0.1f + 0.8f * t);
    normals.emplace_back(1.0f, 0.0f, 0.0f);
  }
  // No clusters (their light mixes the rays of two kinds of entry) and no
  // near sources: patch and sample entries only.
  FinalGatherSettings seen;
  seen.near = 0.0f;
  seen.spots = 0;
  seen.kept = 100000;
  seen.coverage = 1.0;
  FinalGatherSettings every_sample = seen;
  every_sample.sample_kept = 100000;
  every_sample.sample_coverage = 1.0;
  const FinalGather a = build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid,
                                           points, normals, seen);
  const FinalGather b = build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid,
                                           points, normals, every_sample);
  a.validate("seen weights");
  ASSERT_FALSE(a.seen_first.empty());
  ASSERT_GT(a.seen_sample.size(), 0u) << "some rays are read through patch entries";
  for (std::uint32_t src : b.source) ASSERT_GE(src, b.patches + b.clusters) << "samples only";
  // Light varying within every patch, so that the weights matter.
  const std::size_t samples = bake.samples.samples.size();
  std::vector<glm::vec3> patch_light(bake.patches.size(), glm::vec3(0.0f)), sample_light(samples);
  for (std::size_t s = 0; s < samples; ++s)
    sample_light[s] =
        glm::vec3(1.0f + static_cast<float>(s % 7), 0.5f + static_cast<float>(s % 3), 1.0f);
  for (std::size_t p = 0; p < patch_light.size(); ++p) {
    double area = 0.0;
    for (std::uint32_t k = bake.patches.member_first[p]; k < bake.patches.member_first[p + 1];
         ++k) {
      const std::uint32_t s = bake.patches.member_samples[k];
      patch_light[p] += bake.samples.samples[s].area * sample_light[s];
      area += bake.samples.samples[s].area;
    }
    if (area > 0.0) patch_light[p] /= static_cast<float>(area);
  }
  const auto total = [&](const FinalGather& g) {
    std::vector<glm::vec3> e;
    g.irradiance(patch_light, sample_light, e);
    glm::dvec3 t(0.0);
    for (const glm::vec3& v : e) t += glm::dvec3(v);
    return t;
  };
  const glm::dvec3 ta = total(a), tb = total(b);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(ta[c], tb[c], 1e-5 * tb[c]) << c;
  // Each patch's area mean instead (no seen weights): another total.
  FinalGather area_weighted = a;
  area_weighted.seen_first.clear();
  area_weighted.seen_sample.clear();
  area_weighted.seen_weight.clear();
  const glm::dvec3 tarea = total(area_weighted);
  EXPECT_GT(glm::length(tarea - tb), 1e-3 * glm::length(tb))
      << "the area mean gives the same total here: the test cannot tell the weights apart";
}

// A floor half shaded by a board, a wall at its far edge, lit by a sun, a
// point light and a spot: near sources on either side of the shadow's edge,
// some facing each light and some not.
Scene shaded_floor() {
  Scene scene = floor_under_a_board();
  scene.lights.push_back({Light::Type::Directional, "sun", glm::vec3(0.0f),
                          glm::vec3(0.3f, -1.0f, 0.1f), glm::vec3(1.0f, 0.9f, 0.8f), 1.0f});
  Light point{Light::Type::Point,          "lamp", glm::vec3(0.5f, 0.3f, 0.2f), glm::vec3(0.0f),
              glm::vec3(0.2f, 0.4f, 1.0f), 2.0f};
  scene.lights.push_back(point);
  Light spot{Light::Type::Spot, "spot", glm::vec3(-0.5f, 0.4f, 0.0f), glm::vec3(0.2f, -1.0f, 0.0f),
             glm::vec3(1.0f),   3.0f};
  spot.spot_inner_deg = 20.0f;
  spot.spot_outer_deg = 35.0f;
  scene.lights.push_back(spot);
  return scene;
}

// A gather for points a few centimetres above the floor, facing it, across
// the shadow, every ray within a voxel reading near sources.
FinalGather gather_over_the_floor(const RayTracer& tracer, const BakeResult& bake,
                                  FinalGatherSettings fs) {
  const SurfacePatchLookup lookup(bake.voxels, bake.samples, bake.patch_of_sample);
  std::vector<glm::vec3> points, normals;
  for (int i = 0; i < 40; ++i) {
    const float t = static_cast<float>(i) / 39.0f;
    points.emplace_back(-0.9f + 1.8f * t, 0.03f + 0.1f * t, 0.5f - t);
    normals.emplace_back(0.0f, -1.0f, 0.0f);
  }
  fs.near = 1.0f;
  return build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid, points, normals,
                            fs);
}
FinalGather gather_over_the_floor(const RayTracer& tracer, const BakeResult& bake, int rays) {
  FinalGatherSettings fs;
  fs.rays = rays;
  fs.spots = 0;  // the near sources the rows read, and only those
  return gather_over_the_floor(tracer, bake, fs);
}

// The product summed in double from the float rows: the independent
// expectation both row forms are held against.
std::vector<glm::dvec3> product_in_double(const FinalGather& g, const std::vector<glm::vec3>& patch,
                                          const std::vector<glm::vec3>& sample,
                                          const std::vector<glm::vec3>& near) {
  std::vector<glm::dvec3> light;
  for (const glm::vec3& v : patch) light.emplace_back(v);
  // A patch with seen weights reads its samples' light so weighted.
  for (std::size_t p = 0; p + 1 < g.seen_first.size(); ++p) {
    if (g.seen_first[p] == g.seen_first[p + 1]) continue;
    light[p] = glm::dvec3(0.0);
    for (std::uint32_t k = g.seen_first[p]; k < g.seen_first[p + 1]; ++k)
      light[p] += static_cast<double>(g.seen_weight[k]) * glm::dvec3(sample[g.seen_sample[k]]);
  }
  std::vector<glm::dvec3> cluster(g.clusters, glm::dvec3(0.0));
  for (std::size_t p = 0; p < g.patches; ++p)
    cluster[g.cluster_of_patch[p]] += static_cast<double>(g.cluster_share[p]) * light[p];
  light.insert(light.end(), cluster.begin(), cluster.end());
  for (const glm::vec3& v : sample) light.emplace_back(v);
  for (const glm::vec3& v : near) light.emplace_back(v);
  std::vector<glm::dvec3> out(g.points(), glm::dvec3(0.0));
  for (std::size_t i = 0; i < g.points(); ++i)
    for (std::uint64_t k = g.first[i]; k < g.first[i + 1]; ++k)
      out[i] += static_cast<double>(g.weight[k]) * light[g.source[k]];
  return out;
}

TEST(FinalGather, CompactRowsHoldTheFloatRowsExactly) {
  const Scene scene = shaded_floor();
  const BakeResult bake = bake_of(scene, 8);
  const RayTracer tracer(scene);
  for (const int rays : {256, 300}) {
    FinalGather g = gather_over_the_floor(tracer, bake, rays);
    g.validate("floor");
    ASSERT_GT(g.near.size(), 0u);
    ASSERT_EQ(g.compact.size(), g.source.size()) << rays;
    EXPECT_EQ(g.compact_rays, rays);
    // Each entry decodes to its source and to a ray count whose share is
    // the float weight to the last bit.
    const std::uint32_t mask = (1u << g.compact_count_bits) - 1u;
    for (std::size_t k = 0; k < g.source.size(); ++k) {
      EXPECT_EQ(g.compact[k] >> g.compact_count_bits, g.source[k]);
      EXPECT_EQ(static_cast<float>(static_cast<double>(g.compact[k] & mask) / rays), g.weight[k]);
    }
    // Rows read from a bake carry no ray count: the smallest weight gives it.
    FinalGather read = g;
    read.rays = 0;
    read.compact_rows();
    EXPECT_EQ(read.compact, g.compact);
    EXPECT_EQ(read.compact_rays, rays);
  }
}

TEST(FinalGather, CompactAndFloatRowsGiveTheSameProduct) {
  const Scene scene = shaded_floor();
  const BakeResult bake = bake_of(scene, 8);
  const RayTracer tracer(scene);
  FinalGather g = gather_over_the_floor(tracer, bake, 256);
  ASSERT_FALSE(g.compact.empty());
  // Light that differs from source to source, so a misread entry shows.
  std::vector<glm::vec3> patch(g.patches), sample(g.samples), near(g.near.size());
  for (std::size_t i = 0; i < patch.size(); ++i)
    patch[i] = glm::vec3(1.0f + 0.01f * static_cast<float>(i), 0.5f, 2.0f);
  for (std::size_t i = 0; i < sample.size(); ++i)
    sample[i] = glm::vec3(0.3f, 1.0f + 0.002f * static_cast<float>(i), 0.7f);
  for (std::size_t i = 0; i < near.size(); ++i)
    near[i] = glm::vec3(2.0f, 0.1f, 0.5f + 0.001f * static_cast<float>(i));
  const std::vector<glm::dvec3> expected = product_in_double(g, patch, sample, near);
  std::vector<glm::vec3> compact, plain;
  g.irradiance(patch, sample, near, compact);
  // Rows that do not fit the compact form (a weight that is no whole number
  // of rays) fall back to the float rows.
  FinalGather uneven = g;
  uneven.weight[0] *= 0.999f;
  uneven.compact_rows();
  EXPECT_TRUE(uneven.compact.empty());
  g.compact.clear();
  g.irradiance(patch, sample, near, plain);
  // Float sums of up to a few hundred terms: a few float roundings each.
  for (std::size_t i = 0; i < expected.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double tolerance = 1e-5 * std::abs(expected[i][c]) + 1e-7;
      EXPECT_NEAR(compact[i][c], expected[i][c], tolerance) << i;
      EXPECT_NEAR(plain[i][c], expected[i][c], tolerance) << i;
    }
}

// Rows of every length from 0 to 200 entries (so that each wide loop runs
// its full vectors, its half vector and its one-by-one rest), ray counts of
// 1 to 256 of 256 rays, sources spread over a million padded lights.
FinalGather long_random_rows(std::size_t patches, std::size_t near, std::uint64_t seed) {
  Rng rng(seed, 0);
  FinalGather g;
  g.patches = patches;
  g.clusters = 1;
  g.cluster_of_patch.assign(patches, 0);
  g.cluster_share.assign(patches, 1.0f / static_cast<float>(patches));
  g.near.position.assign(near, glm::vec3(0.0f));
  g.near.normal.assign(near, glm::vec3(0.0f, 1.0f, 0.0f));
  g.near.albedo.assign(near, glm::vec3(0.5f));
  g.near.patch.assign(near, 0);
  g.rays = 256;
  g.first.push_back(0);
  const std::size_t sources = patches + 1 + near;
  for (std::size_t row = 0; row <= 200; ++row) {
    for (std::size_t k = 0; k < row; ++k) {
      const auto pick = static_cast<std::size_t>(rng.next() % sources);
      g.source.push_back(static_cast<std::uint32_t>(pick));
      const int count = 1 + static_cast<int>(rng.uniform() * 255.0f);
      g.weight.push_back(static_cast<float>(static_cast<double>(count) / 256.0));
    }
    g.first.push_back(g.source.size());
  }
  return g;
}

TEST(FinalGather, EveryRowLoopGivesTheProductInDouble) {
  FinalGather g = long_random_rows(5000, 1000000, 7);
  g.compact_rows();
  ASSERT_EQ(g.compact.size(), g.source.size());
  Rng rng(11, 0);
  std::vector<glm::vec3> patch(g.patches), near(g.near.size());
  for (glm::vec3& v : patch) v = glm::vec3(rng.uniform(), rng.uniform(), rng.uniform());
  for (glm::vec3& v : near) v = glm::vec3(rng.uniform(), rng.uniform(), 4.0f * rng.uniform());
  const std::vector<glm::dvec3> expected = product_in_double(g, patch, {}, near);
  // The loop the product picked is one this CPU has.
  bool known = false;
  for (const gather_loops::CompactLoop& loop : gather_loops::compact_loops())
    known = known || loop.name == g.compact_loop;
  EXPECT_TRUE(known) << g.compact_loop;
  for (const gather_loops::CompactLoop& loop : gather_loops::compact_loops()) {
    g.compact_loop = loop.name;
    std::vector<glm::vec3> out;
    g.irradiance(patch, {}, near, out);
    ASSERT_EQ(out.size(), expected.size());
    // Up to 200 positive terms summed in float: a relative error of a few
    // hundred float epsilons at most.
    for (std::size_t i = 0; i < expected.size(); ++i)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(out[i][c], expected[i][c], 2e-5 * expected[i][c] + 1e-7)
            << loop.name << ", row " << i << ", channel " << c;
  }
  // The fused loops agree to the bit, so which one timing picks does not
  // change the light; the portable loop is picked only without them.
  std::vector<glm::vec3> first_fused;
  bool any_fused = false;
  for (const gather_loops::CompactLoop& loop : gather_loops::compact_loops()) {
    if (!loop.fused) continue;
    any_fused = true;
    g.compact_loop = loop.name;
    std::vector<glm::vec3> out;
    g.irradiance(patch, {}, near, out);
    if (first_fused.empty())
      first_fused = out;
    else
      for (std::size_t i = 0; i < out.size(); ++i) ASSERT_EQ(out[i], first_fused[i]) << i;
  }
  FinalGather picked = g;
  picked.compact_rows();
  EXPECT_EQ(picked.compact_loop != "sse2", any_fused) << picked.compact_loop;
  g.compact_loop = "no such loop";
  std::vector<glm::vec3> out;
  EXPECT_THROW(g.irradiance(patch, {}, near, out), Error);
}

TEST(FinalGather, NearSourceNamingAMissingPatchIsOneErrorNamingIt) {
  NearSources near;
  for (int i = 0; i < 600; ++i) {  // three batches, the bad ones in the last two
    near.position.emplace_back(0.0f);
    near.normal.emplace_back(0.0f, 1.0f, 0.0f);
    near.albedo.emplace_back(0.5f);
    near.patch.push_back(i == 300 || i == 599 ? 7u : 1u);
  }
  const std::vector<glm::vec3> indirect(3, glm::vec3(1.0f));
  try {
    near_exitance(near, nullptr, {}, {}, indirect);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    // The first bad source, whichever thread met it first.
    EXPECT_NE(std::string(e.what()).find("near source 300 names patch 7 of 3"), std::string::npos)
        << e.what();
  }
}

TEST(FinalGather, NearSourcesLitInBatchesGetEachPointsOwnLight) {
  const Scene scene = shaded_floor();
  const BakeResult bake = bake_of(scene, 8);
  const RayTracer tracer(scene);
  const FinalGather g = gather_over_the_floor(tracer, bake, 256);
  ASSERT_GT(g.near.size(), 300u);  // more than one batch
  std::vector<glm::vec3> indirect(bake.patches.size());
  for (std::size_t p = 0; p < indirect.size(); ++p)
    indirect[p] = glm::vec3(0.01f * static_cast<float>(p), 0.02f, 0.03f);
  const std::vector<glm::vec3> batched = near_exitance(g.near, &tracer, scene.lights, {}, indirect);
  const float eps = 10.0f * tracer.epsilon();
  std::size_t lit = 0, dark = 0;
  for (std::size_t i = 0; i < g.near.size(); ++i) {
    const glm::vec3 e = irradiance_at(tracer, g.near.position[i] + eps * g.near.normal[i],
                                      g.near.normal[i], scene.lights, {}, 4, i);
    const glm::vec3 alone = g.near.albedo[i] * e + indirect[g.near.patch[i]];
    EXPECT_EQ(batched[i], alone) << i;
    const glm::vec3 sun = irradiance_at(tracer, g.near.position[i] + eps * g.near.normal[i],
                                        g.near.normal[i], {scene.lights[0]}, {}, 4, i);
    (glm::dot(sun, glm::vec3(1.0f)) > 0.0f ? lit : dark)++;
  }
  // Both sides of the sun shadow's edge are there.
  EXPECT_GT(lit, 0u);
  EXPECT_GT(dark, 0u);
}

TEST(FinalGather, LightingTheNearSourcesIntoTheProductGivesTheSameLight) {
  // A relighter's frame lights the near sources straight into the
  // product's buffer: the same E to the bit as lighting them on their own
  // and summing the rows after (the samples' spots among them).
  const Scene scene = shaded_floor();
  const BakeResult bake = bake_of(scene, 8);
  const RayTracer tracer(scene);
  FinalGatherSettings fs;
  ASSERT_GT(fs.spots, 0);
  const FinalGather g = gather_over_the_floor(tracer, bake, fs);
  ASSERT_GT(g.spots(), 0u);
  ASSERT_GT(g.spot_base(), 0u);
  std::vector<glm::vec3> patch(g.patches), sample(g.samples), indirect(g.patches);
  for (std::size_t p = 0; p < g.patches; ++p) {
    patch[p] = glm::vec3(0.3f + 0.01f * static_cast<float>(p), 0.5f, 0.2f);
    indirect[p] = glm::vec3(0.01f * static_cast<float>(p), 0.02f, 0.03f);
  }
  for (std::size_t s = 0; s < sample.size(); ++s)
    sample[s] = glm::vec3(0.1f, 0.001f * static_cast<float>(s), 0.4f);
  std::vector<glm::vec3> apart, together;
  g.irradiance(patch, sample, near_exitance(g.near, &tracer, scene.lights, {}, indirect), apart);
  double seconds = -1.0;
  g.irradiance_lighting_near(patch, sample, tracer, scene.lights, {}, indirect, together, &seconds);
  ASSERT_EQ(together.size(), apart.size());
  for (std::size_t i = 0; i < apart.size(); ++i) EXPECT_EQ(together[i], apart[i]) << i;
  EXPECT_GE(seconds, 0.0);
  // A light buffer of the wrong size is one error, as for irradiance().
  std::vector<glm::vec3> short_patch(g.patches - 1);
  EXPECT_THROW(
      g.irradiance_lighting_near(short_patch, sample, tracer, scene.lights, {}, indirect, together),
      Error);
}

TEST(FinalGather, NearSourcesWithFewRaysGoBackToTheirSurface) {
  // The same rays with every near source kept and with those under three
  // rays folded back: each point keeps its rays (its total), every kept
  // near source holds at least three, and fewer are left to light.
  const Scene scene = shaded_floor();
  const BakeResult bake = bake_of(scene, 8);
  const RayTracer tracer(scene);
  FinalGatherSettings all, folded;
  all.near_min_rays = 1;
  folded.near_min_rays = 3;
  all.spots = folded.spots = 0;  // the near sources the rows read
  const FinalGather a = gather_over_the_floor(tracer, bake, all);
  const FinalGather b = gather_over_the_floor(tracer, bake, folded);
  b.validate("folded");
  EXPECT_LT(b.near.size(), a.near.size());
  EXPECT_GT(b.near.size(), 0u);
  EXPECT_LT(b.rays_near, a.rays_near);
  EXPECT_EQ(b.rays_landed, a.rays_landed);
  const std::size_t near_base = b.patches + b.clusters + b.samples;
  std::vector<long> near_rays(b.near.size(), 0);
  for (std::size_t i = 0; i < b.points(); ++i) {
    long ta = 0, tb = 0;
    for (std::uint64_t k = a.first[i]; k < a.first[i + 1]; ++k)
      ta += std::lround(static_cast<double>(a.weight[k]) * a.rays);
    for (std::uint64_t k = b.first[i]; k < b.first[i + 1]; ++k) {
      const long hits = std::lround(static_cast<double>(b.weight[k]) * b.rays);
      tb += hits;
      if (b.source[k] >= near_base) near_rays[b.source[k] - near_base] += hits;
    }
    EXPECT_EQ(ta, tb) << i;
  }
  for (std::size_t j = 0; j < near_rays.size(); ++j) EXPECT_GE(near_rays[j], 3) << j;
  // The folded rows still fit the compact form.
  EXPECT_EQ(b.compact.size(), b.source.size());
}

}  // namespace
}  // namespace bounce
