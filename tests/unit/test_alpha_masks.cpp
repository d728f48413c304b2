// Alpha-masked (cut-out) materials: rays pass the cut-away parts in every
// query (shadow rays, the reference, camera rays), samples carry only the
// solid area, and a mask that cuts everything away leaves the scene as if
// the surface were not there. Masks here are checkers whose solid squares
// are known by construction: a bilinear lookup of a checker crosses 0.5
// exactly on the squares' edges, so a square's centre is solid or cut
// according to its parity alone, and exactly half of the checker is solid.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "base/diagnostics.h"
#include "base/random.h"
#include "gltf_quad.h"
#include "patches/samples.h"
#include "quad_files.h"
#include "raytrace/ray_tracer.h"
#include "reference/path_tracer.h"
#include "runtime/camera_image.h"
#include "scene/alpha_mask.h"
#include "scene/scene_loader.h"
#include "scratch_dir.h"
#include "test_scenes.h"
#include "textured_floor.h"
#include "voxel/voxelization.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

const fs::path kFloorScene = fs::path(BOUNCE_RESOURCE_DIR) / "scenes" / "textured-floor";

// n x n texels, squares of one texel, solid (1) where x + y is even.
std::shared_ptr<const AlphaMask> checker_mask(int n) {
  auto m = std::make_shared<AlphaMask>();
  m->width = m->height = n;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) m->values.push_back((x + y) % 2 == 0 ? 1.0f : 0.0f);
  return m;
}

// Whether the checker's square under texture point (u, v) is solid: row 0
// of the image is at v = 1.
bool checker_solid(int n, double u, double v) {
  const int x = static_cast<int>(std::floor(u * n));
  const int y = static_cast<int>(std::floor((1.0 - v) * n));
  return (x + y) % 2 == 0;
}

constexpr int kTexels = 8;

// An extent x extent floor at y = 0 and, unless `with_quad` is false, a
// quad of the same size at y = 0.5 above it, both facing up; the quad is
// mapped once onto `mask` (u = x / extent, v = z / extent). A vertical sun of
// irradiance 1. With `ceiling`, a ceiling at y = 1 facing down (shading all).
Scene floor_under_quad(std::shared_ptr<const AlphaMask> mask, bool with_quad = true,
                       float extent = 1.0f, bool ceiling = false) {
  Scene s;
  const float e = extent;
  test_scenes::add_quad(s, "floor", {0, 0, 0}, {0, 0, e}, {e, 0, e}, {e, 0, 0}, glm::vec3(0.8f));
  if (ceiling)
    test_scenes::add_quad(s, "ceiling", {0, 1, 0}, {e, 1, 0}, {e, 1, e}, {0, 1, e},
                          glm::vec3(0.5f));
  if (with_quad) {
    test_scenes::add_quad(s, "quad", {0, 0.5f, 0}, {0, 0.5f, e}, {e, 0.5f, e}, {e, 0.5f, 0},
                          glm::vec3(0.2f));
    s.materials.back().alpha_mask = std::move(mask);
  }
  for (std::size_t t = 0; t < s.triangle_count(); ++t) {
    std::array<glm::vec2, 3> uv;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 p = s.vertex(t, k);
      uv[static_cast<std::size_t>(k)] = glm::vec2(p.x / e, p.z / e);
    }
    s.triangle_uv.push_back(uv);
  }
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  s.lights.push_back(sun);
  return s;
}

TEST(AlphaMasks, ShadowRaysPassExactlyTheCutAwaySquares) {
  const Scene s = floor_under_quad(checker_mask(kTexels));
  const RayTracer tracer(s);
  for (int i = 0; i < kTexels; ++i)
    for (int j = 0; j < kTexels; ++j) {
      const double u = (i + 0.5) / kTexels, v = (j + 0.5) / kTexels;
      const glm::vec3 p(static_cast<float>(u), 0.0f, static_cast<float>(v));
      const bool blocked = tracer.occluded(p, glm::vec3(0, 1, 0), 1e-4f, 0.9f);
      EXPECT_EQ(blocked, checker_solid(kTexels, u, v)) << "square " << i << "," << j;
    }
}

TEST(AlphaMasks, CheckerLetsHalfTheSunThrough) {
  const Scene s = floor_under_quad(checker_mask(kTexels));
  const RayTracer tracer(s);
  // Uniform points on the floor, the batched (stream) query.
  constexpr std::size_t kRays = 20000;
  Rng rng(7, 0);
  std::vector<ShadowRay> rays(kRays);
  for (ShadowRay& r : rays) {
    r.origin = glm::vec3(rng.uniform(), 0.0f, rng.uniform());
    r.direction = glm::vec3(0, 1, 0);
    r.t_near = 1e-4f;
    r.t_far = 0.9f;
  }
  std::vector<std::uint8_t> blocked(kRays);
  tracer.occluded(rays.data(), kRays, blocked.data());
  double free = 0.0;
  for (std::uint8_t b : blocked) free += b ? 0.0 : 1.0;
  // Binomial: 4 standard deviations of the mean of kRays draws at p = 0.5.
  const double tolerance = 4.0 * std::sqrt(0.25 / static_cast<double>(kRays));
  EXPECT_NEAR(free / kRays, 0.5, tolerance);
  // And a closest-hit query from above lands on the floor through the holes.
  std::size_t on_floor = 0;
  for (std::size_t k = 0; k < 2000; ++k) {
    const Hit h = tracer.intersect(rays[k].origin + glm::vec3(0, 0.9f, 0), glm::vec3(0, -1, 0));
    ASSERT_TRUE(h.hit);
    const bool floor = s.material_of(h.triangle).name == "floor";
    EXPECT_EQ(floor, blocked[k] == 0) << k;
    on_floor += floor ? 1 : 0;
  }
  EXPECT_GT(on_floor, 0u);
}

TEST(AlphaMasks, ReferenceSeesTheSunThroughTheHolesOnly) {
  const Scene s = floor_under_quad(checker_mask(kTexels));
  const RayTracer tracer(s);
  ReferenceSettings rs;
  rs.samples = 16;
  const ReferencePathTracer pt(tracer, rs);
  std::vector<ReferencePoint> points;
  std::vector<bool> solid;
  for (int i = 0; i < kTexels; ++i)
    for (int j = 0; j < kTexels; ++j) {
      const double u = (i + 0.5) / kTexels, v = (j + 0.5) / kTexels;
      ReferencePoint p;
      p.position = glm::vec3(static_cast<float>(u), 0.0f, static_cast<float>(v));
      p.normal = glm::vec3(0, 1, 0);
      p.albedo = glm::vec3(0.8f);
      points.push_back(p);
      solid.push_back(checker_solid(kTexels, u, v));
    }
  const PointReference r = pt.estimate_points(points);
  for (std::size_t k = 0; k < points.size(); ++k)
    EXPECT_NEAR(r.direct_irradiance[k].g, solid[k] ? 0.0f : 1.0f, 1e-5f) << "point " << k;
}

TEST(AlphaMasks, CameraRaysPassTheHoles) {
  Scene s = floor_under_quad(checker_mask(kTexels), true, 2.0f);
  // Straight above the middle; the quad (2 x 2 at y = 0.5, 9.5 below the
  // camera) fills the view: tan(fov / 2) = 1 / 9.5. A ray through a hole
  // meets the floor 10 / 9.5 times as far from the middle, still on it for
  // the squares' centres.
  s.camera.position = glm::vec3(1.0f, 10.0f, 1.0f);
  s.camera.target = glm::vec3(1.0f, 0.0f, 1.0f);
  s.camera.up = glm::vec3(0.0f, 0.0f, -1.0f);
  s.camera.fov_y_deg = static_cast<float>(2.0 * std::atan(1.0 / 9.5) * 180.0 / std::numbers::pi);
  const RayTracer tracer(s);
  CameraImageSettings settings;
  settings.width = settings.height = 64;
  std::vector<CameraHit> hits;
  render_camera_direct(tracer, settings, hits);
  std::vector<const CameraHit*> at(64 * 64, nullptr);
  for (const CameraHit& h : hits)
    if (h.pixel < at.size()) at[h.pixel] = &h;
  // Pixel (x, y) looks at the quad point x = 2 (x + 0.5) / 64, z = 2 (y + 0.5) / 64
  // (up is -z: image rows go +z). Check the centre pixel of every square:
  // on a solid square the primary hit is the quad, in a hole the floor.
  const int per_square = 64 / kTexels;
  for (int i = 0; i < kTexels; ++i)
    for (int j = 0; j < kTexels; ++j) {
      const int px = per_square * i + per_square / 2, py = per_square * j + per_square / 2;
      const double u = (px + 0.5) / 64.0, v = (py + 0.5) / 64.0;
      const CameraHit* h = at[static_cast<std::size_t>(py * 64 + px)];
      ASSERT_NE(h, nullptr);
      const bool solid = checker_solid(kTexels, u, v);
      EXPECT_NEAR(h->position.y, solid ? 0.5 : 0.0, 1e-4) << "square " << i << "," << j;
      if (solid) {
        EXPECT_NEAR(h->position.x, 2.0 * u, 1e-3);
        EXPECT_NEAR(h->position.z, 2.0 * v, 1e-3);
      }
    }
  // The reference's primary rays alike: a solid square shows the quad's
  // albedo 0.2 under the sun, a hole the floor (0.8 where the sun reaches
  // it through a hole, 0 in the quad's shadow).
  ReferenceSettings rs;
  rs.samples = 4;
  const ReferencePathTracer pt(tracer, rs);
  ReferenceRenderer renderer(pt, 64, 64);
  renderer.add_samples(4);
  const ReferenceImages ref = renderer.images();
  for (int i = 0; i < kTexels; ++i)
    for (int j = 0; j < kTexels; ++j) {
      const int px = per_square * i + per_square / 2, py = per_square * j + per_square / 2;
      const double u = (px + 0.5) / 64.0, v = (py + 0.5) / 64.0;
      const glm::vec3 full = ref.full.at(px, py), indirect = ref.indirect.at(px, py);
      const float direct = full.g - indirect.g;
      if (checker_solid(kTexels, u, v))
        EXPECT_NEAR(direct, 0.2f, 1e-3f) << "square " << i << "," << j;
      else
        EXPECT_TRUE(std::abs(direct) < 1e-3f || std::abs(direct - 0.8f) < 1e-3f)
            << "square " << i << "," << j << ": " << direct;
    }
}

TEST(AlphaMasks, SamplesCarryOnlyTheSolidArea) {
  const Scene s = floor_under_quad(checker_mask(kTexels));
  const RayTracer tracer(s);
  const Voxelization vox = voxelize(s, VoxelGrid(s.bounds(), 4));
  const SampleSet set = generate_samples(s, tracer, vox, SamplingSettings{});
  double quad = 0.0, floor = 0.0;
  for (const Sample& x : set.samples) {
    const std::string& name = s.material_of(x.triangle).name;
    if (name == "floor") floor += x.area;
    if (name != "quad") continue;
    quad += x.area;
    // No sample stands on a hole (its position is where a ray stopped).
    const float alpha = s.material_of(x.triangle).alpha_mask->lookup({x.position.x, x.position.z});
    EXPECT_GE(alpha, 0.5f - 1e-3f) << x.position.x << " " << x.position.z;
  }
  EXPECT_NEAR(floor, 1.0, 1e-4);  // the floor under it is whole
  // Half the quad, as the lattice of mask lookups measures each cell: 16 x 16
  // lookups per cell at most, an error of a few tenths of a percent over
  // many cells.
  EXPECT_NEAR(quad, 0.5, 0.01);
  EXPECT_NEAR(quad + set.cut_away_area, 1.0, 1e-4);
}

TEST(AlphaMasks, FullyCutQuadSamplesAsIfItWereNotThere) {
  // The ceiling keeps the bounds (so the grid) the same without the quad.
  const Scene with = floor_under_quad(AlphaMask::constant(0.0f), true, 1.0f, true);
  const Scene without = floor_under_quad(nullptr, false, 1.0f, true);
  ASSERT_EQ(with.bounds().lo, without.bounds().lo);
  ASSERT_EQ(with.bounds().hi, without.bounds().hi);
  const RayTracer tw(with), to(without);
  const Voxelization vw = voxelize(with, VoxelGrid(with.bounds(), 4));
  const Voxelization vo = voxelize(without, VoxelGrid(without.bounds(), 4));
  const SampleSet a = generate_samples(with, tw, vw, SamplingSettings{});
  const SampleSet b = generate_samples(without, to, vo, SamplingSettings{});
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (std::size_t k = 0; k < a.samples.size(); ++k) {
    EXPECT_EQ(a.samples[k].position, b.samples[k].position) << k;
    EXPECT_EQ(a.samples[k].area, b.samples[k].area) << k;
    EXPECT_EQ(a.samples[k].triangle, b.samples[k].triangle) << k;
  }
  // Rays: nothing between the floor and the ceiling, as without the quad.
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) {
      const glm::vec3 p((static_cast<float>(i) + 0.5f) / 16, 0.0f,
                        (static_cast<float>(j) + 0.5f) / 16);
      EXPECT_FALSE(tw.occluded(p, glm::vec3(0, 1, 0), 1e-4f, 0.9f)) << i << "," << j;
      const Hit h = tw.intersect(p + glm::vec3(0, 0.9f, 0), glm::vec3(0, -1, 0));
      EXPECT_EQ(with.material_of(h.triangle).name, "floor") << i << "," << j;
    }
  EXPECT_NEAR(a.cut_away_area, 1.0, 1e-5);
  EXPECT_EQ(b.cut_away_area, 0.0);
  EXPECT_EQ(a.sampled_area, b.sampled_area);
}

TEST(AlphaMasks, SolidFractionOfACheckerIsHalf) {
  const auto mask = checker_mask(kTexels);
  // The whole map as two triangles, and a triangle of one square's size
  // straddling four squares (any half-texel shift of a checker is half solid).
  EXPECT_NEAR(mask->solid_fraction({{{0, 0}, {1, 0}, {1, 1}}}, 1.0f, 0.5f), 0.5f, 0.02f);
  EXPECT_NEAR(mask->solid_fraction({{{0, 0}, {1, 1}, {0, 1}}}, 1.0f, 0.5f), 0.5f, 0.02f);
  EXPECT_EQ(AlphaMask::constant(1.0f)->solid_fraction({{{0, 0}, {1, 0}, {1, 1}}}, 1.0f, 0.5f),
            1.0f);
  EXPECT_EQ(AlphaMask::constant(1.0f)->solid_fraction({{{0, 0}, {1, 0}, {1, 1}}}, 0.4f, 0.5f),
            0.0f);
  // Inside one solid square, and inside one cut square.
  const float t = 1.0f / kTexels;
  EXPECT_EQ(mask->solid_fraction(
                {{{0.1f * t, 1 - 0.9f * t}, {0.9f * t, 1 - 0.9f * t}, {0.5f * t, 1 - 0.1f * t}}},
                1.0f, 0.5f),
            1.0f);
  EXPECT_EQ(mask->solid_fraction(
                {{{1.1f * t, 1 - 0.9f * t}, {1.9f * t, 1 - 0.9f * t}, {1.5f * t, 1 - 0.1f * t}}},
                1.0f, 0.5f),
            0.0f);
}

// Files: OBJ map_d and glTF alphaMode MASK through the loader.
std::string warnings_of(const Diagnostics& d) {
  std::string text;
  for (const Diagnostic& w : d.warnings()) text += w.where + ": " + w.message + "\n";
  return text;
}

TEST(AlphaMaskFiles, FloorScenesFenceIsHalfCutAway) {
  Diagnostics d;
  const Scene s = SceneLoader(d).load(kFloorScene);
  EXPECT_TRUE(d.warnings().empty()) << warnings_of(d);
  const Material* fence = nullptr;
  for (const Material& m : s.materials)
    if (m.name == "fence") fence = &m;
  ASSERT_NE(fence, nullptr);
  ASSERT_NE(fence->alpha_mask, nullptr);
  EXPECT_EQ(fence->alpha_cutoff, 0.5f);
  EXPECT_EQ(fence->texture, nullptr);
  // fence-mask.png: 8 x 8, alpha 255 where (x / 2 + y / 2) is even, else 0.
  ASSERT_EQ(fence->alpha_mask->width, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      EXPECT_EQ(fence->alpha_mask->values[static_cast<std::size_t>(y * 8 + x)],
                (x / 2 + y / 2) % 2 == 0 ? 1.0f : 0.0f);
  for (std::size_t t = 0; t < s.triangle_count(); ++t)
    EXPECT_EQ(s.masked(t), &s.material_of(t) == fence);
}

// The textured-floor scene copied to a scratch folder with its fence
// textured by an image that also holds its mask as alpha (map_Kd and map_d
// the same file: what a glTF MASK material is). The fence (Kd 0.5) is mapped
// once onto the image; the image's alpha is fence-mask.png's checker
// (make_fence_mask.py: 8 x 8, solid where x / 2 + y / 2 is even).
class TexturedFence : public ::testing::Test {
 protected:
  test::ScratchDir dir{"bounce-textured-fence"};
  Diagnostics diagnostics;

  static bool solid_texel(int x, int y) { return (x / 2 + y / 2) % 2 == 0; }

  // The scene with the fence's material lines "map_Kd image" and "map_d image".
  Scene load_with_fence_image(const std::string& image) {
    for (const auto& entry : fs::directory_iterator(kFloorScene))
      fs::copy_file(entry.path(), dir / entry.path().filename().string());
    std::ifstream in(kFloorScene / "textured-floor.mtl");
    std::string mtl((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string mask_line = "map_d fence-mask.png";
    const std::size_t at = mtl.find(mask_line);
    EXPECT_NE(at, std::string::npos);
    mtl.replace(at, mask_line.size(), "map_Kd " + image + "\nmap_d " + image);
    std::ofstream(dir / "textured-floor.mtl") << mtl;
    return SceneLoader(diagnostics).load(dir.path());
  }

  // An 8 x 8 RGBA PNG with the mask's alpha, sRGB colour `solid` where the
  // mask keeps the texel and `hole` (at alpha 0) where it cuts it away.
  void write_fence_image(const std::string& name, const glm::ivec3& solid, const glm::ivec3& hole) {
    std::vector<std::uint8_t> rgba;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        const glm::ivec3 c = solid_texel(x, y) ? solid : hole;
        for (int k = 0; k < 3; ++k) rgba.push_back(static_cast<std::uint8_t>(c[k]));
        rgba.push_back(solid_texel(x, y) ? 255 : 0);
      }
    const std::string file = (dir / name).string();
    auto out = OIIO::ImageOutput::create(file);
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(8, 8, 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // stored as given
    ASSERT_TRUE(out->open(file, spec) && out->write_image(OIIO::TypeDesc::UINT8, rgba.data()) &&
                out->close());
  }

  // The mean of the image's linear colour over its solid texels, from its
  // construction, times the fence's Kd 0.5.
  static glm::dvec3 solid_mean(const glm::ivec3& solid) {
    glm::dvec3 sum(0.0);
    int count = 0;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        if (solid_texel(x, y)) {
          sum += glm::dvec3(test::decode(solid.r), test::decode(solid.g), test::decode(solid.b));
          ++count;
        }
    return 0.5 * sum / static_cast<double>(count);
  }

  // The fence's flat albedo, every fence sample's albedo, and the albedo
  // where rays land on the fence (only ever on its solid part) are
  // `expected`. Every solid texel holds the same colour, so any lattice
  // that averages solid texels only gives that colour: the tolerance is
  // float rounding.
  static void expect_fence_albedo(const Scene& s, const glm::dvec3& expected) {
    const Material* fence = nullptr;
    for (const Material& m : s.materials)
      if (m.name == "fence") fence = &m;
    ASSERT_NE(fence, nullptr);
    ASSERT_NE(fence->texture, nullptr);
    ASSERT_NE(fence->alpha_mask, nullptr);
    constexpr double kTolerance = 1e-5;
    EXPECT_TRUE(test::near(glm::dvec3(fence->albedo), expected, kTolerance))
        << fence->albedo.r << " " << fence->albedo.g << " " << fence->albedo.b;

    double area = 0.0;
    for (const Sample& x : test::textured_samples(s).samples) {
      if (&s.material_of(x.triangle) != fence) continue;
      area += x.area;
      EXPECT_TRUE(test::near(glm::dvec3(x.albedo), expected, kTolerance))
          << x.albedo.r << " " << x.albedo.g << " " << x.albedo.b << " at " << x.position.x << " "
          << x.position.y;
    }
    EXPECT_NEAR(area, 1.0, 0.02);  // half of the 2 x 1 fence

    const RayTracer tracer(s);
    // Rays from behind the fence (z = 2) towards the wall, on a lattice of
    // 8 points per texel, so that many land next to a hole.
    int landed = 0;
    for (int i = 0; i < 64; ++i)
      for (int j = 0; j < 32; ++j) {
        const glm::vec3 from(-1.0f + (static_cast<float>(i) + 0.5f) / 32.0f,
                             (static_cast<float>(j) + 0.5f) / 32.0f, 2.0f);
        const Hit hit = tracer.intersect(from, {0.0f, 0.0f, -1.0f});
        if (!hit.hit || &s.material_of(hit.triangle) != fence) continue;
        ++landed;
        const glm::vec3 p(from.x, from.y, 1.0f);
        const glm::dvec3 albedo(s.albedo_at(hit.triangle, p));
        EXPECT_TRUE(test::near(albedo, expected, kTolerance))
            << albedo.r << " " << albedo.g << " " << albedo.b << " at " << p.x << " " << p.y;
      }
    EXPECT_NEAR(landed, 64 * 32 / 2, 64);
  }
};

// The shipped mask image as the fence's colour too: white by construction,
// so the fence's albedo is its Kd, as the OBJ's untextured fence has it;
// neither the holes nor their edges darken it.
TEST_F(TexturedFence, ShippedMaskAsItsColourLeavesTheKd) {
  const Scene s = load_with_fence_image("fence-mask.png");
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  expect_fence_albedo(s, solid_mean({255, 255, 255}));
}

// The holes hold another colour than the solid squares (as painters leave
// them): it counts nowhere, not in the flat albedo, not in any sample's
// mean, not where a ray lands next to a hole.
TEST_F(TexturedFence, ColourInTheHolesCountsNowhere) {
  const glm::ivec3 solid(200, 150, 60), hole(30, 90, 240);
  write_fence_image("fence-colour.png", solid, hole);
  const Scene s = load_with_fence_image("fence-colour.png");
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  expect_fence_albedo(s, solid_mean(solid));
}

class AlphaMaskFile : public test::QuadFiles {
 protected:
  void expect_one_warning_naming(const std::string& what) const {
    ASSERT_EQ(diagnostics.warnings().size(), 1u) << warnings_of(diagnostics);
    const Diagnostic w = diagnostics.warnings()[0];
    EXPECT_NE((w.where + w.message).find(what), std::string::npos) << w.where << ": " << w.message;
  }
};

TEST_F(AlphaMaskFile, GreyMapDIsItsValue) {
  // A 2 x 1 grey image without alpha (PGM): white, black.
  write("grey.pgm", std::string("P5\n2 1\n255\n") + '\xff' + '\x00');
  const Scene s = load_obj_quad("map_d grey.pgm");
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  const Material& m = s.materials.at(0);
  ASSERT_NE(m.alpha_mask, nullptr);
  EXPECT_EQ(m.alpha_mask->values, (std::vector<float>{1.0f, 0.0f}));
  // Left half of the quad solid, right half cut (bilinear, wrapping: the
  // value crosses 0.5 at u = 0.5 and u = 0 / 1).
  const RayTracer tracer(s);
  EXPECT_TRUE(tracer.intersect({0.25f, 0.5f, 1.0f}, {0, 0, -1}).hit);
  EXPECT_FALSE(tracer.intersect({0.75f, 0.5f, 1.0f}, {0, 0, -1}).hit);
}

TEST_F(AlphaMaskFile, MissingMaskWarnsOnceNamingItAndKeepsTheSurfaceWhole) {
  const Scene s = load_obj_quad("map_d nowhere.png");
  expect_one_warning_naming("nowhere.png");
  EXPECT_EQ(s.materials.at(0).alpha_mask, nullptr);
  EXPECT_FALSE(s.has_masks());
}

TEST_F(AlphaMaskFile, UnreadableMaskWarnsOnceNamingIt) {
  write("broken.png", "\x89PNG\r\n\x1a\nthis is not an image");
  const Scene s = load_obj_quad("map_d broken.png");
  expect_one_warning_naming("broken.png");
  EXPECT_EQ(s.materials.at(0).alpha_mask, nullptr);
}

// A unit quad in z = 0 facing +z with its base colour texture `image`
// (tests/unit/gltf_quad.h).
class GltfMask : public AlphaMaskFile {
 protected:
  Scene load_gltf_quad(const std::string& image, const std::string& material,
                       const std::string& factor = "[0.5, 0.5, 0.5, 1]") {
    const std::string json = test::gltf_quad(image, material, factor);
    write("quad.gltf", json);
    return SceneLoader(diagnostics).load(dir / "quad.gltf");
  }
};

TEST_F(GltfMask, MaskModeCutsWhereTheBaseColoursAlphaIsBelowTheCutoff) {
  fs::copy_file(kFloorScene / "fence-mask.png", dir / "mask.png");
  const Scene s = load_gltf_quad("mask.png", R"(, "alphaMode": "MASK", "alphaCutoff": 0.25)");
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  const Material& m = s.materials.at(0);
  ASSERT_NE(m.alpha_mask, nullptr);
  EXPECT_EQ(m.alpha_cutoff, 0.25f);
  EXPECT_NE(m.texture, nullptr);
  // Texel (0, 0), the top left of the image (glTF texture coordinates
  // (0, 0): the quad's corner x = 0, y = 1), is solid, texel (2, 0) cut.
  const RayTracer tracer(s);
  EXPECT_TRUE(tracer.intersect({0.5f / 8, 1 - 0.5f / 8, 1.0f}, {0, 0, -1}).hit);
  EXPECT_FALSE(tracer.intersect({2.5f / 8, 1 - 0.5f / 8, 1.0f}, {0, 0, -1}).hit);
}

TEST_F(GltfMask, OpaqueAndBlendAreWhole) {
  fs::copy_file(kFloorScene / "fence-mask.png", dir / "mask.png");
  EXPECT_FALSE(load_gltf_quad("mask.png", R"(, "alphaMode": "BLEND")").has_masks());
  EXPECT_FALSE(load_gltf_quad("mask.png", "").has_masks());
}

TEST_F(GltfMask, CutoffOutsideZeroToOneWarnsNamingTheFile) {
  fs::copy_file(kFloorScene / "fence-mask.png", dir / "mask.png");
  const Scene s = load_gltf_quad("mask.png", R"(, "alphaMode": "MASK", "alphaCutoff": 2.5)");
  expect_one_warning_naming("quad.gltf");
  EXPECT_NE(diagnostics.warnings()[0].message.find("alphaCutoff"), std::string::npos);
  EXPECT_EQ(s.materials.at(0).alpha_cutoff, 0.5f);
}

TEST_F(GltfMask, FactorBelowTheCutoffCutsEverything) {
  fs::copy_file(kFloorScene / "fence-mask.png", dir / "mask.png");
  const Scene s = load_gltf_quad("mask.png", R"(, "alphaMode": "MASK")", "[0.5, 0.5, 0.5, 0.3]");
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  const RayTracer tracer(s);
  EXPECT_FALSE(tracer.intersect({0.5f / 8, 1 - 0.5f / 8, 1.0f}, {0, 0, -1}).hit);
}

TEST_F(GltfMask, FactorBelowTheCutoffWithoutTextureOrCoordinatesCutsEverything) {
  const Scene s =
      load_gltf_quad("", R"(, "alphaMode": "MASK", "alphaCutoff": 0.6)", "[0.5, 0.5, 0.5, 0.5]");
  // Nothing to warn about: a constant mask needs no texture coordinates.
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  const RayTracer tracer(s);
  EXPECT_FALSE(tracer.intersect({0.5f, 0.5f, 1.0f}, {0, 0, -1}).hit);
  // And one above the cutoff is whole: no mask at all.
  EXPECT_FALSE(
      load_gltf_quad("", R"(, "alphaMode": "MASK", "alphaCutoff": 0.4)", "[0.5, 0.5, 0.5, 0.5]")
          .has_masks());
}

}  // namespace
}  // namespace bounce
