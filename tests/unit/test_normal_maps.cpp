// Tangent-space normal maps: read from OBJ (map_bump / bump holding an RGB
// normal map, norm, the -bm scale) and glTF (normalTexture and its scale)
// as stored, not decoded from sRGB; grey height maps and missing files get
// one warning naming the file. The shipped textured-floor wall's map,
// wall-ridges.png, is a washboard of facets tilted 30 degrees about v,
// alternately towards -u and +u in 8 columns, so each texel's direction is
// known by construction. The bake does not use normal maps: its samples
// come out the same with and without one.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>

#include "base/diagnostics.h"
#include "gltf_quad.h"
#include "patches/samples.h"
#include "quad_files.h"
#include "raytrace/ray_tracer.h"
#include "scene/scene_loader.h"
#include "scene/texture.h"
#include "voxel/voxelization.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

const fs::path kFloorScene = fs::path(BOUNCE_RESOURCE_DIR) / "scenes" / "textured-floor";

std::string warnings_of(const Diagnostics& d) {
  std::string text;
  for (const Diagnostic& w : d.warnings()) text += w.where + ": " + w.message + "\n";
  return text;
}

const Material& material(const Scene& s, const std::string& name) {
  for (const Material& m : s.materials)
    if (m.name == name) return m;
  throw std::runtime_error("no material " + name);
}

// The direction a normal-map texel stands for.
glm::dvec3 decoded(const Texture& map, glm::vec2 uv) {
  return 2.0 * glm::dvec3(map.lookup(uv)) - 1.0;
}

// The facets' normals, from the tilt alone.
const double kSin = std::sin(std::numbers::pi / 6.0), kCos = std::cos(std::numbers::pi / 6.0);

TEST(NormalMaps, WallReadsItsRidgesAsTangentSpaceNormals) {
  Diagnostics d;
  const Scene s = SceneLoader(d).load(kFloorScene);
  EXPECT_TRUE(d.warnings().empty()) << warnings_of(d);
  const Material& wall = material(s, "wall");
  ASSERT_NE(wall.normal_map, nullptr);
  EXPECT_EQ(wall.normal_scale, 1.0f);
  ASSERT_EQ(s.triangle_uv.size(), s.triangle_count());
  for (int column = 0; column < 8; ++column)
    for (const float v : {0.1f, 0.5f, 0.9f}) {
      const glm::vec2 uv((static_cast<float>(column) + 0.5f) / 8.0f, v);
      const glm::dvec3 n = decoded(*wall.normal_map, uv);
      const double x = column % 2 == 0 ? -kSin : kSin;
      // 8-bit rounding: within half a step (1/255) of the stored value.
      EXPECT_NEAR(n.x, x, 0.01) << "column " << column;
      EXPECT_NEAR(n.y, 0.0, 0.01) << "column " << column;
      EXPECT_NEAR(n.z, kCos, 0.01) << "column " << column;
    }
  // Other materials have none.
  EXPECT_EQ(material(s, "floor").normal_map, nullptr);
  EXPECT_EQ(material(s, "fence").normal_map, nullptr);
}

TEST(NormalMaps, BakeSamplesIgnoreTheNormalMap) {
  Diagnostics d;
  const Scene with = SceneLoader(d).load(kFloorScene);
  Scene without = with;
  for (Material& m : without.materials) m.normal_map = nullptr;
  const auto samples = [](const Scene& s) {
    const RayTracer tracer(s);
    const Voxelization vox = voxelize(s, VoxelGrid(s.bounds(), 8));
    SampleSet set = generate_samples(s, tracer, vox, SamplingSettings{});
    apply_surface_textures(s, vox, set);
    return set;
  };
  const SampleSet a = samples(with), b = samples(without);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (std::size_t k = 0; k < a.samples.size(); ++k) {
    EXPECT_EQ(a.samples[k].position, b.samples[k].position);
    EXPECT_EQ(a.samples[k].normal, b.samples[k].normal);
    EXPECT_EQ(a.samples[k].albedo, b.samples[k].albedo);
    EXPECT_EQ(a.samples[k].area, b.samples[k].area);
  }
}

class NormalMapFiles : public test::QuadFiles {
 protected:
  void SetUp() override { fs::copy_file(kFloorScene / "wall-ridges.png", dir / "ridges.png"); }
  void expect_one_warning_naming(const std::string& file) const {
    ASSERT_EQ(diagnostics.warnings().size(), 1u) << warnings_of(diagnostics);
    const Diagnostic w = diagnostics.warnings()[0];
    EXPECT_NE((w.where + w.message).find(file), std::string::npos) << w.where << ": " << w.message;
  }
};

TEST_F(NormalMapFiles, NormWithBumpMultiplierScalesTheMap) {
  const Scene s = load_obj_quad("norm -bm 0.5 ridges.png");
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  const Material& m = s.materials.at(0);
  ASSERT_NE(m.normal_map, nullptr);
  EXPECT_EQ(m.normal_scale, 0.5f);
  EXPECT_NEAR(decoded(*m.normal_map, {1.0f / 16.0f, 0.5f}).x, -kSin, 0.01);
}

TEST_F(NormalMapFiles, BumpHoldingAnRgbNormalMapIsReadAsOne) {
  const Scene s = load_obj_quad("bump -bm 2 ridges.png");
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  ASSERT_NE(s.materials.at(0).normal_map, nullptr);
  EXPECT_EQ(s.materials.at(0).normal_scale, 2.0f);
}

TEST_F(NormalMapFiles, GreyHeightMapWarnsOnceNamingItAndIsNotRead) {
  // A 2 x 1 grey image (PGM): a height map, no directions.
  write("height.pgm", std::string("P5\n2 1\n255\n") + '\xc0' + '\x40');
  const Scene s = load_obj_quad("map_bump height.pgm");
  expect_one_warning_naming("height.pgm");
  EXPECT_EQ(s.materials.at(0).normal_map, nullptr);
}

TEST_F(NormalMapFiles, ColourImageInTheBumpSlotWarnsOnceNamingIt) {
  fs::copy_file(kFloorScene / "checker.png", dir / "checker.png");
  const Scene s = load_obj_quad("map_bump checker.png");
  expect_one_warning_naming("checker.png");
  EXPECT_EQ(s.materials.at(0).normal_map, nullptr);
}

TEST_F(NormalMapFiles, MissingNormalMapWarnsOnceNamingIt) {
  const Scene s = load_obj_quad("norm nowhere.png");
  expect_one_warning_naming("nowhere.png");
  EXPECT_EQ(s.materials.at(0).normal_map, nullptr);
  EXPECT_EQ(s.materials.at(0).albedo, glm::vec3(0.5f));
}

TEST_F(NormalMapFiles, GltfNormalTextureWithScale) {
  write("quad.gltf",
        test::gltf_quad("ridges.png", R"(, "normalTexture": {"index": 0, "scale": 0.25})",
                        "[0.5, 0.5, 0.5, 1]"));
  const Scene s = SceneLoader(diagnostics).load(dir / "quad.gltf");
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  const Material& m = s.materials.at(0);
  ASSERT_NE(m.normal_map, nullptr);
  EXPECT_EQ(m.normal_scale, 0.25f);
  // As stored, while the same file as a colour texture is decoded from sRGB.
  ASSERT_NE(m.texture, nullptr);
  EXPECT_NEAR(decoded(*m.normal_map, {1.0f / 16.0f, 0.5f}).z, kCos, 0.01);
  EXPECT_LT(m.texture->lookup({1.0f / 16.0f, 0.5f}).r, 0.06f);  // sRGB 64 -> 0.05
}

}  // namespace
}  // namespace bounce
