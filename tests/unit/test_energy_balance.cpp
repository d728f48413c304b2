// Closure and balanced form factors: every row sums to the share of its
// patch's light that lands on sampled surface, reciprocity holds to float
// rounding, and closed rooms conserve energy so that stiff albedos solve.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bake/bake.h"
#include "base/form_factor_kernel.h"
#include "base/random.h"
#include "formfactor/balance.h"
#include "formfactor/closure.h"
#include "patches/surface_patch_lookup.h"
#include "raytrace/ray_tracer.h"
#include "reference/path_tracer.h"
#include "runtime/area_lights.h"
#include "runtime/direct_light.h"
#include "runtime/final_gather.h"
#include "runtime/final_gather_build.h"
#include "scene/scene_loader.h"
#include "test_scenes.h"

namespace bounce {
namespace {

BakeResult bake(const Scene& scene, int voxel) {
  BakeSettings s;
  s.voxel_resolution = voxel;
  s.codec = CodecChoice::Dense;
  s.transport.bounces = 1;
  s.transport.backend = TransportSettings::Backend::OpenBLAS;
  s.pictures = false;
  Diagnostics d;
  Progress progress;
  return Baker(scene, s, d).run(progress);
}

std::vector<double> row_sums(const FormFactorMatrix& f) {
  std::vector<double> rows(f.n, 0.0);
  for (std::size_t p = 0; p < f.n; ++p)
    for (std::size_t q = 0; q < f.n; ++q) rows[p] += f(p, q);
  return rows;
}

// The largest |A_p F_pq - A_q F_qp| relative to A_p F_pq's float rounding.
double reciprocity_in_ulps(const FormFactorMatrix& f, const std::vector<float>& area) {
  double worst = 0.0;
  for (std::size_t p = 0; p < f.n; ++p)
    for (std::size_t q = p + 1; q < f.n; ++q) {
      const double a = static_cast<double>(area[p]) * f(p, q);
      const double b = static_cast<double>(area[q]) * f(q, p);
      const double scale = std::max(std::abs(a), std::abs(b));
      if (scale == 0.0) continue;
      worst = std::max(worst, std::abs(a - b) / (scale * 0x1p-24));
    }
  return worst;
}

TEST(BalanceFormFactors, RowsReachTheirTargetsAndTheExchangeIsSymmetric) {
  // A dense random F, far from reciprocal and from its targets: the
  // balancing must still land every row on its closure.
  const std::size_t n = 60;
  Rng rng(7, 1);
  FormFactorMatrix f;
  f.n = n;
  f.values.assign(n * n, 0.0f);
  std::vector<float> area(n), closure(n);
  for (std::size_t p = 0; p < n; ++p) {
    area[p] = 0.1f + rng.uniform();
    closure[p] = 0.5f + 0.5f * rng.uniform();
    for (std::size_t q = 0; q < n; ++q)
      if (q != p) f.values[p * n + q] = 0.03f * rng.uniform();
  }
  EXPECT_GT(reciprocity_in_ulps(f, area), 1e5);  // not reciprocal before
  const BalanceStats stats = balance_form_factors(f, area, closure);
  EXPECT_TRUE(stats.converged) << stats.residual;
  const std::vector<double> rows = row_sums(f);
  for (std::size_t p = 0; p < n; ++p) EXPECT_NEAR(rows[p], closure[p], 2e-6) << p;
  // One float rounding of x_p S_pq x_q / A_p each way, and of S itself.
  EXPECT_LE(reciprocity_in_ulps(f, area), 4.0);
  for (std::size_t p = 0; p < n; ++p)
    EXPECT_NEAR(stats.row_scale[p], closure[p] / (0.03 * (n - 1) / 2.0), 0.6) << p;
}

TEST(BalanceFormFactors, AlreadyBalancedInputIsLeftAsItIs) {
  // A reciprocal F whose rows already equal the closures: x = 1 at once.
  const std::size_t n = 4;
  FormFactorMatrix f;
  f.n = n;
  f.values = {0,     0.5f,  0.25f, 0.25f, 0.5f,  0,     0.25f, 0.25f,
              0.25f, 0.25f, 0,     0.5f,  0.25f, 0.25f, 0.5f,  0};
  const std::vector<float> area(n, 2.0f), closure(n, 1.0f);
  const std::vector<float> before(f.values.begin(), f.values.end());
  const BalanceStats stats = balance_form_factors(f, area, closure);
  EXPECT_TRUE(stats.converged);
  EXPECT_EQ(stats.iterations, 0);
  for (std::size_t i = 0; i < n * n; ++i) EXPECT_FLOAT_EQ(f.values[i], before[i]);
}

TEST(Closure, ClosedFurnaceIsExactlyOneAndItsRowsToo) {
  const BakeResult r = bake(test_scenes::furnace_box(), 4);
  ASSERT_EQ(r.closure.closure.size(), r.patches.size());
  for (std::size_t p = 0; p < r.patches.size(); ++p) EXPECT_EQ(r.closure.closure[p], 1.0f) << p;
  // Raw rows over-count near edges; balanced rows sit on 1.
  EXPECT_GT(r.checks_raw.row_sum_max, 1.0 + 1e-4);
  const std::vector<double> rows = row_sums(r.form_factors);
  for (std::size_t p = 0; p < rows.size(); ++p) EXPECT_NEAR(rows[p], 1.0, 2e-6) << p;
  EXPECT_EQ(r.checks.rows_above_closure, 0u);
  std::vector<float> area;
  for (const Patch& p : r.patches.patches) area.push_back(p.area);
  EXPECT_LE(reciprocity_in_ulps(r.form_factors, area), 4.0);
}

TEST(Closure, OpenBoxRowsEqualTheAnalyticClosure) {
  // The unit cube without its lid (y = 1): light leaving a point escapes by
  // the point's form factor to the opening, so a patch's exact closure is
  // 1 - (area mean over its surface of F(x -> opening)).
  Scene scene = test_scenes::furnace_box(glm::vec3(0.5f), glm::vec3(0.0f));
  // Drop the two triangles of the face y = 1 (vertices 2, 3, 6, 7).
  for (std::size_t t = scene.triangles.size(); t-- > 0;) {
    const glm::uvec3 tri = scene.triangles[t];
    bool top = true;
    for (int k = 0; k < 3; ++k) top = top && scene.positions[tri[k]].y == 1.0f;
    if (!top) continue;
    scene.triangles.erase(scene.triangles.begin() + static_cast<std::ptrdiff_t>(t));
    scene.triangle_material.erase(scene.triangle_material.begin() + static_cast<std::ptrdiff_t>(t));
    scene.triangle_mesh.erase(scene.triangle_mesh.begin() + static_cast<std::ptrdiff_t>(t));
  }
  scene.meshes[0].triangle_count = static_cast<std::uint32_t>(scene.triangles.size());
  ASSERT_EQ(scene.triangles.size(), 10u);
  const BakeResult r = bake(scene, 4);
  const glm::vec3 opening[4] = {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}};
  const std::size_t n = r.patches.size();
  const std::vector<double> rows = row_sums(r.form_factors);
  double worst_sigma = 0.0, weighted_exact = 0.0, weighted_measured = 0.0, total = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    // The exact escape, integrated over the patch's carried polygons with a
    // 4 x 4 midpoint rule per fan triangle.
    double escape = 0.0, area = 0.0;
    for (std::uint32_t k = r.patches.member_first[p]; k < r.patches.member_first[p + 1]; ++k) {
      const std::uint32_t s = r.patches.member_samples[k];
      const glm::vec3 normal = r.samples.samples[s].normal;
      for (std::uint32_t c = r.samples.carried_first[s]; c < r.samples.carried_first[s + 1]; ++c) {
        const CarriedArea& piece = r.samples.carried[c];
        const glm::vec3* poly = &r.samples.carried_vertices[piece.first_vertex];
        for (std::uint32_t v = 1; v + 1 < piece.vertex_count; ++v) {
          const glm::vec3 a = poly[0], b = poly[v], d = poly[v + 1];
          const double tri_area = 0.5 * glm::length(glm::cross(b - a, d - a));
          constexpr int kM = 4;
          for (int i = 0; i < kM; ++i)
            for (int j = 0; i + j < kM; ++j) {
              // Upward sub-triangle centroids of a kM x kM subdivision, plus
              // the downward ones: kM^2 equal parts.
              for (int down = 0; down < 2; ++down) {
                if (down && i + j + 1 >= kM) continue;
                const float u = (static_cast<float>(i) + (down ? 2.0f : 1.0f) / 3.0f) / kM;
                const float w = (static_cast<float>(j) + (down ? 2.0f : 1.0f) / 3.0f) / kM;
                const glm::vec3 x = a + u * (b - a) + w * (d - a);
                escape +=
                    tri_area / (kM * kM) * point_to_polygon_form_factor(x, normal, opening, 4);
              }
            }
          area += tri_area;
        }
      }
    }
    const double exact = 1.0 - escape / area;
    const double c = r.closure.closure[p];
    const double sigma = std::sqrt(std::max(exact * (1.0 - exact), 1e-4) /
                                   static_cast<double>(r.closure.rays_per_patch));
    worst_sigma = std::max(worst_sigma, std::abs(c - exact) / sigma);
    EXPECT_NEAR(rows[p], c, 2e-6) << "row of patch " << p << " is not its closure";
    const double pa = r.patches.patches[p].area;
    weighted_exact += pa * exact;
    weighted_measured += pa * c;
    total += pa;
  }
  std::printf(
      "closure: open box, %zu patches, worst |measured - exact| = %.2f sigma, mean %.5f vs "
      "exact %.5f\n",
      n, worst_sigma, weighted_measured / total, weighted_exact / total);
  // Stratified rays land well inside the binomial standard error; 4 sigma
  // over ~90 patches would fail on a biased estimate.
  EXPECT_LT(worst_sigma, 4.0);
  EXPECT_NEAR(weighted_measured / total, weighted_exact / total, 2e-3);
  EXPECT_LT(r.closure.min, 0.999);  // the box is open: some light escapes
}

TEST(Closure, AlbedoOneInAClosedRoomIsAClearErrorNotAHang) {
  // Balanced rows sum to 1, so with albedo 1 the light never settles:
  // K = infinity and auto must refuse at once, naming the cause.
  const BakeResult r = bake(test_scenes::furnace_box(), 4);
  const std::vector<glm::vec3> albedo(r.patches.size(), glm::vec3(1.0f));
  for (const int k : {TransportSettings::kInfiniteBounces, TransportSettings::kAutoBounces}) {
    TransportSettings s;
    s.bounces = k;
    s.backend = TransportSettings::Backend::OpenBLAS;
    Diagnostics d;
    try {
      compute_transport(r.form_factors, albedo, s, nullptr, d);
      ADD_FAILURE() << "albedo 1 solved at K = " << k;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("energy is not conserved"), std::string::npos)
          << e.what();
    }
  }
  // Albedo 0.9999, the largest a scene may have, still solves, within 0.5%
  // of the closed room's rho / (1 - rho).
  const std::vector<glm::vec3> bright(r.patches.size(), glm::vec3(0.9999f));
  TransportSettings s;
  s.bounces = TransportSettings::kInfiniteBounces;
  s.backend = TransportSettings::Backend::OpenBLAS;
  Diagnostics d;
  const TransportResult t = compute_transport(r.form_factors, bright, s, nullptr, d);
  const std::size_t n = r.patches.size();
  const double rho = 0.9999f, ideal = rho / (1.0 - rho);
  for (std::size_t p = 0; p < n; ++p) {
    double sum = 0.0;
    for (std::size_t q = 0; q < n; ++q) sum += t.channels[0].t[p * n + q];
    EXPECT_NEAR(sum, ideal, 5e-3 * ideal) << p;
  }
}

// The Cornell box without its two blocks, lit by its ceiling light only.
Scene empty_cornell_box() {
  Diagnostics d;
  const Scene full = SceneLoader(d).load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-box");
  Scene s = full;
  s.lights.clear();
  s.triangles.clear();
  s.triangle_material.clear();
  s.triangle_mesh.clear();
  s.meshes.clear();
  for (std::size_t m = 0; m < full.meshes.size(); ++m) {
    if (full.meshes[m].name.find("Box") != std::string::npos) continue;
    MeshInfo mesh = full.meshes[m];
    mesh.first_triangle = static_cast<std::uint32_t>(s.triangles.size());
    for (std::uint32_t t = full.meshes[m].first_triangle;
         t < full.meshes[m].first_triangle + full.meshes[m].triangle_count; ++t) {
      s.triangles.push_back(full.triangles[t]);
      s.triangle_material.push_back(full.triangle_material[t]);
      s.triangle_mesh.push_back(static_cast<std::uint32_t>(s.meshes.size()));
    }
    s.meshes.push_back(mesh);
  }
  return s;
}

TEST(Closure, EmptyCornellBoxIndirectOverDirectPerWallMatchesThePathTracer) {
  // Each wall's indirect / direct irradiance over its central half: the
  // bake's final gather of b + T b against the path tracer, which shares
  // nothing with the form factors. Closed-row form factors must not add
  // light (the raw quadrature gave +2.5% to +5% on every wall).
  const Scene scene = empty_cornell_box();
  ASSERT_EQ(scene.triangles.size(), 12u);  // 5 walls and the light
  BakeSettings bs;
  bs.voxel_resolution = 10;
  bs.codec = CodecChoice::Dense;
  bs.transport.bounces = TransportSettings::kInfiniteBounces;
  bs.transport.backend = TransportSettings::Backend::OpenBLAS;
  bs.pictures = false;
  Diagnostics d;
  Progress progress;
  const BakeResult r = Baker(scene, bs, d).run(progress);
  const RayTracer tracer(scene);
  const std::vector<AreaLight> area = area_lights(scene);
  const std::size_t n = r.patches.size();
  std::vector<glm::vec3> irradiance(n), sample_irradiance(r.samples.samples.size());
  direct_irradiance(tracer, r.samples, r.patches, {}, area, 8, irradiance, sample_irradiance);
  const std::vector<glm::vec3> b = first_bounce(r.patches, irradiance);
  std::vector<glm::vec3> reflected(n), indirect(n);
  for (std::size_t p = 0; p < n; ++p) {
    glm::vec3 tb(0.0f);
    for (int c = 0; c < 3; ++c) {
      const auto& t = r.transport.channel(c).t;
      for (std::size_t q = 0; q < n; ++q) tb[c] += t[p * n + q] * b[q][c];
    }
    reflected[p] = b[p] + tb;
    indirect[p] = tb;
  }
  const std::vector<glm::vec3> sample_light =
      sample_exitance(r.samples, r.patches, sample_irradiance, indirect);
  // Points on a 5 x 5 grid over each wall's central half, a hair off it.
  struct Wall {
    const char* name;
    glm::vec3 centre, u, v, normal;
  };
  const Bounds box = scene.bounds();
  const glm::vec3 lo = box.lo, hi = box.hi, mid = 0.5f * (lo + hi), size = hi - lo;
  const Wall walls[] = {
      {"floor", {mid.x, lo.y, mid.z}, {size.x, 0, 0}, {0, 0, size.z}, {0, 1, 0}},
      {"ceiling", {mid.x, 1.98f, mid.z}, {size.x, 0, 0}, {0, 0, size.z}, {0, -1, 0}},
      {"back", {mid.x, mid.y, lo.z + 0.02f}, {size.x, 0, 0}, {0, size.y, 0}, {0, 0, 1}},
      {"left", {lo.x + 0.02f, mid.y, mid.z}, {0, size.y, 0}, {0, 0, size.z}, {1, 0, 0}},
      {"right", {hi.x - 0.01f, mid.y, mid.z}, {0, size.y, 0}, {0, 0, size.z}, {-1, 0, 0}}};
  ReferenceSettings rs;
  rs.samples = 4000;
  const ReferencePathTracer pt(tracer, rs);
  const SurfacePatchLookup lookup(r.voxels, r.samples, r.patch_of_sample);
  for (const Wall& w : walls) {
    std::vector<glm::vec3> points, normals;
    std::vector<ReferencePoint> ref_points;
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) {
        // Onto the wall itself: from the room's centre along the wall.
        const glm::vec3 target = w.centre + (static_cast<float>(i) / 4.0f - 0.5f) * 0.5f * w.u +
                                 (static_cast<float>(j) / 4.0f - 0.5f) * 0.5f * w.v;
        const glm::vec3 from = target + 0.3f * w.normal;
        const Hit h = tracer.intersect(from, -w.normal);
        ASSERT_TRUE(h.hit) << w.name;
        const glm::vec3 x = from - h.t * w.normal;
        points.push_back(x);
        normals.push_back(w.normal);
        ref_points.push_back({x, w.normal, glm::vec3(0.5f), glm::vec3(0.0f)});
      }
    FinalGatherSettings fs;
    fs.rays = 2048;
    std::vector<glm::vec3> gathered;
    const FinalGather g =
        build_final_gather(tracer, lookup, r.patches.patches, r.voxels.grid, points, normals, fs);
    g.irradiance(reflected, sample_light, near_exitance(g.near, &tracer, {}, area, indirect),
                 gathered);
    const PointReference ref = pt.estimate_points(ref_points);
    glm::dvec3 bounce_direct(0.0), bounce_indirect(0.0), ref_direct(0.0), ref_indirect(0.0),
        ref_var(0.0);
    for (std::size_t k = 0; k < points.size(); ++k) {
      bounce_direct += glm::dvec3(
          irradiance_at(tracer, points[k] + 1e-4f * normals[k], normals[k], {}, area, 8, k));
      bounce_indirect += glm::dvec3(gathered[k]);
      ref_direct += glm::dvec3(ref.direct_irradiance[k]);
      ref_indirect += glm::dvec3(ref.indirect_irradiance[k]);
      ref_var += glm::dvec3(ref.indirect_variance[k]);
    }
    for (int c = 0; c < 3; ++c) {
      // The ceiling gets no direct light from the lamp under it: its
      // indirect light itself is compared there.
      const bool lit = ref_direct[c] > 0.0;
      const double ours = lit ? bounce_indirect[c] / bounce_direct[c] : bounce_indirect[c];
      const double theirs = lit ? ref_indirect[c] / ref_direct[c] : ref_indirect[c];
      const double sigma = std::sqrt(ref_var[c]) / (lit ? ref_direct[c] : 1.0);
      std::printf("empty box %-8s channel %c: %s %.4f, reference %.4f +- %.4f (%+.2f%%)\n", w.name,
                  "RGB"[c], lit ? "indirect/direct" : "indirect", ours, theirs, sigma,
                  100.0 * (ours / theirs - 1.0));
      // Measured -0.2% .. -1.3% (the raw quadrature: +2.5% .. +5%; with the
      // gather's sample entries capped at 64 whatever the rays: -1.5% ..
      // -2.4%).
      EXPECT_NEAR(ours, theirs, 0.015 * theirs + 3.0 * sigma) << w.name << " channel " << c;
    }
  }
}

}  // namespace
}  // namespace bounce
