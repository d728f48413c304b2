// Emissive textures make textured area lights. The shipped textured-lamp
// scene's lamp (1 x 1, Ke 4) emits through half-lit.png, white on the half
// over x < 0 and black on the other, so by construction it sends out exactly
// half the light of the same lamp untextured, all of it from one half: the
// expectations below compare the two lamps, in the bake's samples and direct
// light and in the reference path tracer. File handling (a missing texture,
// map_Ke without Ke, glTF's emissiveFactor) is checked on small written
// scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/diagnostics.h"
#include "gltf_quad.h"
#include "patches/samples.h"
#include "quad_files.h"
#include "raytrace/ray_tracer.h"
#include "reference/path_tracer.h"
#include "runtime/area_lights.h"
#include "runtime/direct_light.h"
#include "scene/scene_loader.h"
#include "scene/texture.h"
#include "voxel/voxelization.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

const fs::path kLampScene = fs::path(BOUNCE_RESOURCE_DIR) / "scenes" / "textured-lamp";
constexpr float kKe = 4.0f;  // the lamp's Ke

std::string warnings_of(const Diagnostics& d) {
  std::string text;
  for (const Diagnostic& w : d.warnings()) text += w.where + ": " + w.message + "\n";
  return text;
}

Scene load_lamp_scene() {
  Diagnostics d;
  Scene s = SceneLoader(d).load(kLampScene);
  EXPECT_TRUE(d.warnings().empty()) << warnings_of(d);
  return s;
}

const Material& material(const Scene& s, const std::string& name) {
  for (const Material& m : s.materials)
    if (m.name == name) return m;
  throw std::runtime_error("no material " + name);
}

std::size_t first_triangle_of(const Scene& s, const std::string& material_name) {
  for (std::size_t t = 0; t < s.triangle_count(); ++t)
    if (s.material_of(t).name == material_name) return t;
  throw std::runtime_error("no triangle of " + material_name);
}

// The same scene with the lamp untextured: Ke everywhere on it.
Scene untextured(Scene s) {
  for (Material& m : s.materials)
    if (m.emission_texture) {
      m.emission = m.emission_factor;
      m.emission_texture = nullptr;
    }
  return s;
}

// The same scene with only the lit half of the lamp, untextured: the lamp's
// corners at x = 0.5 moved to x = 0. It emits what the textured lamp
// should, from where it should (the texture's blend across its middle texel
// column, 1/64 of the lamp, aside).
Scene lit_half_only(Scene s) {
  const std::size_t t = first_triangle_of(s, "lamp");
  for (std::size_t k = t; k < s.triangle_count() && s.material_of(k).name == "lamp"; ++k)
    for (int c = 0; c < 3; ++c) {
      glm::vec3& p = s.positions[s.triangles[k][c]];
      if (p.x > 0.0f) p.x = 0.0f;
    }
  return untextured(std::move(s));
}

// Floor points: the centres of a k x k grid over the 2 x 2 floor.
std::vector<glm::vec3> floor_points(int k) {
  std::vector<glm::vec3> points;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      points.emplace_back(-1.0f + 2.0f * (static_cast<float>(i) + 0.5f) / static_cast<float>(k),
                          0.0f,
                          -1.0f + 2.0f * (static_cast<float>(j) + 0.5f) / static_cast<float>(k));
  return points;
}

TEST(EmissiveTextures, LampSceneReadsItsHalfLitTexture) {
  const Scene s = load_lamp_scene();
  const Material& lamp = material(s, "lamp");
  ASSERT_NE(lamp.emission_texture, nullptr);
  EXPECT_EQ(lamp.emission_factor, glm::vec3(kKe));
  // The flat emission is the factor times the texture's mean, one half.
  EXPECT_NEAR(lamp.emission.r, 0.5f * kKe, 1e-5f);
  EXPECT_TRUE(lamp.is_emissive());
  const std::size_t t = first_triangle_of(s, "lamp");
  for (const float z : {-0.3f, 0.0f, 0.3f}) {
    EXPECT_NEAR(s.emission_at(t, {-0.25f, 1.0f, z}).r, kKe, 1e-5f) << "white half, z " << z;
    EXPECT_NEAR(s.emission_at(t, {0.25f, 1.0f, z}).r, 0.0f, 1e-5f) << "black half, z " << z;
  }
  // An untextured emitter answers its emission everywhere.
  const Scene u = untextured(s);
  EXPECT_EQ(u.emission_at(t, {0.25f, 1.0f, 0.0f}), glm::vec3(kKe));
}

TEST(EmissiveTextures, SamplesEmitTheTexturesMeanOverWhatTheyCarry) {
  const Scene s = load_lamp_scene();
  const RayTracer tracer(s);
  const Voxelization vox = voxelize(s, VoxelGrid(s.bounds(), 8));
  SampleSet set = generate_samples(s, tracer, vox, SamplingSettings{});
  const SampleSet before = set;
  EXPECT_GT(apply_surface_textures(s, vox, set), 0u);
  double area = 0.0, power = 0.0;
  float lo = kKe, hi = 0.0f;
  for (std::size_t k = 0; k < set.samples.size(); ++k) {
    const Sample& x = set.samples[k];
    if (s.material_of(x.triangle).name != "lamp") {
      // The floor has no texture: left as sampled, bit for bit.
      EXPECT_EQ(x.emission, before.samples[k].emission);
      EXPECT_EQ(x.albedo, before.samples[k].albedo);
      continue;
    }
    area += static_cast<double>(x.area);
    power += static_cast<double>(x.area) * static_cast<double>(x.emission.r);
    lo = std::min(lo, x.emission.r);
    hi = std::max(hi, x.emission.r);
  }
  ASSERT_NEAR(area, 1.0, 1e-3);
  // Half the untextured lamp's Ke x area.
  EXPECT_NEAR(power, 0.5 * kKe, 0.01 * kKe) << "emitted power of the lamp's samples";
  // Samples follow the texture: those on one half carry its emission.
  EXPECT_GT(hi, 0.9f * kKe);
  EXPECT_LT(lo, 0.1f * kKe);
}

// Sum of the direct irradiance over the floor's grid points, and the part
// of it over x < 0, with the bake's area lights.
struct FloorLight {
  double total = 0.0, left = 0.0;
};

FloorLight bake_floor_light(const Scene& s) {
  const RayTracer tracer(s);
  const std::vector<AreaLight> lights = area_lights(s);
  FloorLight out;
  std::uint64_t seed = 0;
  for (const glm::vec3& p : floor_points(16)) {
    const double e = irradiance_at(tracer, p, {0, 1, 0}, {}, lights, 8, seed++).r;
    out.total += e;
    if (p.x < 0.0f) out.left += e;
  }
  return out;
}

TEST(EmissiveTextures, BakeDirectLightIsHalfTheUntexturedLampsFromItsLitHalf) {
  const Scene s = load_lamp_scene();
  const FloorLight textured = bake_floor_light(s);
  const FloorLight plain = bake_floor_light(untextured(s));
  const FloorLight half = bake_floor_light(lit_half_only(s));
  ASSERT_GT(plain.total, 0.0);
  std::cout << "[ measured ] bake direct light on the floor, textured / untextured lamp: "
            << textured.total / plain.total << ", textured / lit half alone "
            << textured.total / half.total << ", share on x < 0: " << textured.left / textured.total
            << " (lit half alone " << half.left / half.total << ")\n";
  EXPECT_NEAR(textured.total / plain.total, 0.5, 0.01);
  // As much as the lit half alone, and as much of it on the floor's half
  // under it; the untextured lamp lights both halves alike.
  EXPECT_NEAR(textured.total / half.total, 1.0, 0.02);
  EXPECT_NEAR(textured.left / textured.total, half.left / half.total, 0.01);
  EXPECT_NEAR(plain.left / plain.total, 0.5, 0.01);
  EXPECT_GT(textured.left / textured.total, 0.55);
}

TEST(EmissiveTextures, ReferenceDirectLightIsHalfTheUntexturedLampsFromItsLitHalf) {
  const Scene s = load_lamp_scene();
  const Scene u = untextured(s);
  std::vector<ReferencePoint> points;
  for (const glm::vec3& p : floor_points(10)) {
    ReferencePoint r;
    r.position = p;
    r.normal = glm::vec3(0.0f, 1.0f, 0.0f);
    r.albedo = glm::vec3(0.5f);
    points.push_back(r);
  }
  ReferenceSettings rs;
  rs.samples = 256;
  // The direct light summed over all points, and over the strips beyond
  // the lamp's sides (|x| > 0.5), where the lit half's light falls off
  // from x = -0.5 and x = 0 alike whichever way one looks.
  struct Sums {
    double total = 0.0, left = 0.0, right = 0.0;
  };
  const auto sums = [&](const Scene& scene) {
    const RayTracer tracer(scene);
    const PointReference r = ReferencePathTracer(tracer, rs).estimate_points(points);
    Sums out;
    for (std::size_t k = 0; k < points.size(); ++k) {
      const auto e = static_cast<double>(r.direct_irradiance[k].r);
      out.total += e;
      if (points[k].position.x < -0.5f) out.left += e;
      if (points[k].position.x > 0.5f) out.right += e;
    }
    return out;
  };
  const Sums textured = sums(s), plain = sums(u), half = sums(lit_half_only(s));
  ASSERT_GT(plain.total, 0.0);
  std::cout << "[ measured ] reference direct light on the floor, textured / untextured lamp: "
            << textured.total / plain.total << ", textured / lit half alone "
            << textured.total / half.total
            << "; left strip / right strip: " << textured.left / textured.right
            << " (lit half alone " << half.left / half.right << ", untextured lamp "
            << plain.left / plain.right << ")\n";
  EXPECT_NEAR(textured.total / plain.total, 0.5, 0.02);
  EXPECT_NEAR(textured.total / half.total, 1.0, 0.03);
  // Within 4%: a lamp drawn with each triangle's mean emission (no lookup
  // per point) comes out 8% off here, an untextured one 55%.
  EXPECT_NEAR(textured.left / textured.right, half.left / half.right,
              0.04 * half.left / half.right);
}

class EmissiveTextureFiles : public test::QuadFiles {
 protected:
  // A quad with Ke 2 and map_Ke `file` that cannot be used: one warning
  // naming the file, and the emission is Ke alone.
  void expect_one_warning_and_ke(const std::string& file) {
    const Scene s = load_obj_quad("Ke 2 2 2\nmap_Ke " + file);
    ASSERT_EQ(diagnostics.warnings().size(), 1u) << warnings_of(diagnostics);
    const Diagnostic w = diagnostics.warnings()[0];
    EXPECT_NE((w.where + w.message).find(file), std::string::npos) << w.message;
    EXPECT_EQ(s.materials.at(0).emission_texture, nullptr);
    EXPECT_EQ(s.materials.at(0).emission, glm::vec3(2.0f));
  }
};

TEST_F(EmissiveTextureFiles, MissingTextureWarnsOnceNamingItAndEmitsKe) {
  expect_one_warning_and_ke("nowhere.png");
}

TEST_F(EmissiveTextureFiles, UnreadableTextureWarnsOnceNamingItAndEmitsKe) {
  write("broken.png", "\x89PNG\r\n\x1a\nthis is not an image");
  expect_one_warning_and_ke("broken.png");
}

TEST_F(EmissiveTextureFiles, MapKeWithoutKeTakesFactorOne) {
  fs::copy_file(kLampScene / "half-lit.png", dir / "half-lit.png");
  const Scene s = load_obj_quad("map_Ke half-lit.png");
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  const Material& m = s.materials.at(0);
  ASSERT_NE(m.emission_texture, nullptr);
  EXPECT_EQ(m.emission_factor, glm::vec3(1.0f));
  EXPECT_NEAR(m.emission.g, 0.5f, 1e-5f);
}

TEST_F(EmissiveTextureFiles, GltfEmissiveTextureTimesEmissiveFactor) {
  fs::copy_file(kLampScene / "half-lit.png", dir / "half-lit.png");
  write("quad.gltf",
        test::gltf_quad("half-lit.png",
                        R"(, "emissiveTexture": {"index": 0}, "emissiveFactor": [2, 1, 0.5])",
                        "[0.5, 0.5, 0.5, 1]"));
  const Scene s = SceneLoader(diagnostics).load(dir / "quad.gltf");
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  const Material& m = s.materials.at(0);
  ASSERT_NE(m.emission_texture, nullptr);
  EXPECT_EQ(m.emission_factor, glm::vec3(2.0f, 1.0f, 0.5f));
  EXPECT_NEAR(m.emission.r, 1.0f, 1e-5f);
  EXPECT_NEAR(m.emission.b, 0.25f, 1e-5f);
  // glTF's v runs down and the image is white on its left: x < 0.5 emits.
  EXPECT_NEAR(s.emission_at(0, {0.25f, 0.5f, 0.0f}).r, 2.0f, 1e-5f);
  EXPECT_NEAR(s.emission_at(0, {0.75f, 0.5f, 0.0f}).r, 0.0f, 1e-5f);
}

}  // namespace
}  // namespace bounce
