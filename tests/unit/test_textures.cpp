// Colour textures: decoding (sRGB to linear), file lookup (case-insensitive
// fallback, one warning for a missing or unreadable file), the bake's sample
// albedo (the texture's mean over the surface each sample carries), and the
// reference path tracer and camera pictures that look the texel up where a
// ray lands. The shipped textured-floor scene is an 8 x 8 checker of two
// sRGB colours, so every expectation here is known by construction.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/diagnostics.h"
#include "patches/samples.h"
#include "quad_files.h"
#include "raytrace/ray_tracer.h"
#include "reference/path_tracer.h"
#include "runtime/camera_image.h"
#include "scene/alpha_mask.h"
#include "scene/scene_loader.h"
#include "scene/texture.h"
#include "scratch_dir.h"
#include "test_scenes.h"
#include "textured_floor.h"
#include "voxel/voxelization.h"
#include "warnings_text.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

const fs::path kSponza = fs::path(BOUNCE_SHARED_DATA_DIR) / "dabrovic-sponza" / "sun.json";

using test::colour_a;
using test::colour_b;
using test::kFloorScene;
using test::near;
using test::warnings_of;

const Material& floor_material(const Scene& s) {
  for (const Material& m : s.materials)
    if (m.name == "floor") return m;
  throw std::runtime_error("no floor material");
}

TEST(Textures, FloorSceneLoadsItsCheckerDecodedToLinear) {
  Diagnostics d;
  const Scene s = SceneLoader(d).load(kFloorScene);
  EXPECT_TRUE(d.warnings().empty()) << warnings_of(d);
  const Material& floor = floor_material(s);
  ASSERT_NE(floor.texture, nullptr);
  ASSERT_EQ(s.triangle_uv.size(), s.triangle_count());
  // Half the squares of each colour: the flat albedo is their mean.
  EXPECT_TRUE(near(glm::dvec3(floor.albedo), 0.5 * (colour_a() + colour_b()), 2e-3))
      << floor.albedo.x << " " << floor.albedo.y << " " << floor.albedo.z;
  // The centre of every square is one colour or the other, alternating.
  std::size_t a = 0, b = 0;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) {
      const glm::vec3 p(-1.0f + (static_cast<float>(i) + 0.5f) / 4.0f, 0.0f,
                        -1.0f + (static_cast<float>(j) + 0.5f) / 4.0f);
      for (std::size_t t = 0; t < s.triangle_count(); ++t) {
        if (s.material_of(t).name != "floor") continue;
        const glm::dvec3 albedo(s.albedo_at(t, p));
        const bool is_a = near(albedo, colour_a(), 2e-3), is_b = near(albedo, colour_b(), 2e-3);
        EXPECT_TRUE(is_a || is_b) << "square " << i << "," << j;
        (is_a ? a : b) += 1;
        break;
      }
    }
  EXPECT_EQ(a, 32u);
  EXPECT_EQ(b, 32u);
}

TEST(Textures, SampleAlbedoIsTheTexturesMeanOverWhatEachSampleCarries) {
  Diagnostics d;
  const Scene s = SceneLoader(d).load(kFloorScene);
  test::expect_floor_samples_carry_the_checker(s);
}

// The camera straight above sees the floor fill the 64 x 64 picture, one
// square per 8 x 8 pixels; under the vertical sun (irradiance 1) the direct
// light of a square's centre pixel is its albedo.
void expect_checker(const RgbFloatImage& direct, const char* what) {
  std::size_t a = 0, b = 0;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) {
      const glm::dvec3 v(direct.at(8 * i + 4, 8 * j + 4));
      const bool is_a = near(v, colour_a(), 1e-2), is_b = near(v, colour_b(), 1e-2);
      EXPECT_TRUE(is_a || is_b) << what << ": pixel of square " << i << "," << j << " is " << v.x
                                << " " << v.y << " " << v.z;
      (is_a ? a : b) += 1;
    }
  EXPECT_EQ(a, 32u) << what;
  EXPECT_EQ(b, 32u) << what;
}

TEST(Textures, CameraPicturesShowTheTexture) {
  Diagnostics d;
  const Scene s = SceneLoader(d).load(kFloorScene);
  const RayTracer tracer(s);
  CameraImageSettings settings;
  settings.width = settings.height = 64;
  std::vector<CameraHit> hits;
  const CameraImages images = render_camera_direct(tracer, settings, hits);
  expect_checker(images.direct, "bounce camera image");

  ReferenceSettings rs;
  rs.samples = 4;
  const ReferencePathTracer pt(tracer, rs);
  ReferenceRenderer renderer(pt, 64, 64);
  renderer.add_samples(4);
  const ReferenceImages ref = renderer.images();
  RgbFloatImage direct(64, 64);
  for (std::size_t p = 0; p < direct.pixels.size(); ++p)
    direct.pixels[p] = ref.full.pixels[p] - ref.indirect.pixels[p];
  expect_checker(direct, "reference");
}

TEST(Textures, ReferenceBouncesOffTheTexel) {
  // A floor lit from straight above (irradiance 1), textured left half red,
  // right half blue (linear), and a point 5 cm above the middle of the red
  // half facing down: ~99% of what it sees is red floor, so its indirect
  // light is ~0.8 red and ~0.1 blue. Had the path tracer bounced off the
  // material's mean colour instead of the texel, the two would be equal.
  Scene s;
  test_scenes::add_quad(s, "floor", {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});
  auto texture = std::make_shared<Texture>();
  Texture::Level level;
  level.width = 64;
  level.height = 1;
  for (int x = 0; x < 64; ++x)
    level.texels.push_back(x < 32 ? glm::vec3(0.8f, 0.1f, 0.1f) : glm::vec3(0.1f, 0.1f, 0.8f));
  texture->levels.push_back(level);
  texture->mean = glm::vec3(0.45f, 0.1f, 0.45f);
  s.materials[0].texture = texture;
  s.materials[0].texture_factor = glm::vec3(1.0f);
  s.materials[0].albedo = texture->mean;
  for (std::size_t t = 0; t < s.triangle_count(); ++t) {
    std::array<glm::vec2, 3> uv;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 p = s.vertex(t, k);
      uv[static_cast<std::size_t>(k)] = glm::vec2((p.x + 1.0f) / 2.0f, (p.z + 1.0f) / 2.0f);
    }
    s.triangle_uv.push_back(uv);
  }
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  s.lights.push_back(sun);

  const RayTracer tracer(s);
  ReferenceSettings rs;
  rs.samples = 2000;
  const ReferencePathTracer pt(tracer, rs);
  ReferencePoint above_red;
  above_red.position = glm::vec3(-0.5f, 0.05f, 0.0f);
  above_red.normal = glm::vec3(0.0f, -1.0f, 0.0f);
  const glm::vec3 e = pt.estimate_points({above_red}).indirect_irradiance[0];
  EXPECT_NEAR(e.r, 0.8f, 0.05f);
  EXPECT_NEAR(e.b, 0.1f, 0.02f);
}

// Writes `pixels` (width x 1, RGBA, channels interleaved) to `file` as
// given: the writer is told they are unassociated, so it stores them without
// dividing colour by alpha.
template <class T>
void write_rgba(const fs::path& file, int width, OIIO::TypeDesc type,
                const std::vector<T>& pixels) {
  auto out = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(out) << OIIO::geterror();
  OIIO::ImageSpec spec(width, 1, 4, type);
  spec.attribute("oiio:UnassociatedAlpha", 1);
  ASSERT_TRUE(out->open(file.string(), spec) && out->write_image(type, pixels.data()) &&
              out->close())
      << out->geterror();
}

// A PNG's colour under partial and zero alpha is read as stored, not
// multiplied by alpha (OpenImageIO's default), and its alpha is unchanged:
// a cut-out's edges and holes keep their colour.
TEST(TextureAlpha, PngColourUnderPartialAlphaIsReadAsStored) {
  const test::ScratchDir dir("bounce-texture-alpha");
  const fs::path png = dir / "partial.png";
  const std::vector<std::uint8_t> rgba = {200, 100, 50, 128, 40, 80, 160, 0, 10, 20, 30, 255};
  write_rgba(png, 3, OIIO::TypeDesc::UINT8, rgba);
  std::string error;
  const std::optional<ImagePixels> pixels = read_image_pixels(png, error);
  ASSERT_TRUE(pixels) << error;
  ASSERT_EQ(pixels->channels, 4);
  EXPECT_EQ(pixels->alpha_channel, 3);
  for (std::size_t i = 0; i < rgba.size(); ++i)
    EXPECT_NEAR(pixels->pixels[i], rgba[i] / 255.0f, 1e-6f) << "value " << i;
  const auto texture = load_texture(png, error);
  ASSERT_NE(texture, nullptr) << error;
  for (std::size_t t = 0; t < 3; ++t)
    EXPECT_TRUE(near(glm::dvec3(texture->levels[0].texels[t]),
                     glm::dvec3(test::decode(rgba[4 * t]), test::decode(rgba[4 * t + 1]),
                                test::decode(rgba[4 * t + 2])),
                     1e-6))
        << "texel " << t;
  const auto mask = load_alpha_mask(png, AlphaSource::AlphaOnly, error);
  ASSERT_NE(mask, nullptr) << error;
  EXPECT_EQ(mask->values, (std::vector<float>{128.0f / 255.0f, 0.0f, 1.0f}));

  // The same file embedded in a mesh file (decoded from memory) reads the same.
  auto embedded = std::make_shared<EmbeddedImage>();
  embedded->name = "model.glb#texture 0";
  embedded->format_hint = "png";
  embedded->bytes = image_file_bytes(png, error);
  const std::optional<ImagePixels> from_memory = read_image_pixels(ImageSource(embedded), error);
  ASSERT_TRUE(from_memory) << error;
  EXPECT_EQ(from_memory->pixels, pixels->pixels);
}

// OpenEXR stores colour multiplied by alpha: it is divided back where alpha
// is above 0, so that every format gives the colour of what is there.
TEST(TextureAlpha, ExrColourIsDividedByItsAlpha) {
  const test::ScratchDir dir("bounce-texture-alpha");
  const fs::path exr = dir / "associated.exr";
  // (0.8, 0.4, 0.2) at alpha 0.5 and 0.25, stored multiplied; opaque (0.1, 0.2, 0.3).
  const std::vector<float> rgba = {0.4f,  0.2f,  0.1f, 0.5f, 0.2f, 0.1f,
                                   0.05f, 0.25f, 0.1f, 0.2f, 0.3f, 1.0f};
  write_rgba(exr, 3, OIIO::TypeDesc::FLOAT, rgba);
  std::string error;
  const auto texture = load_texture(exr, error);
  ASSERT_NE(texture, nullptr) << error;
  const std::vector<glm::dvec3> expected = {{0.8, 0.4, 0.2}, {0.8, 0.4, 0.2}, {0.1, 0.2, 0.3}};
  for (std::size_t t = 0; t < 3; ++t)
    EXPECT_TRUE(near(glm::dvec3(texture->levels[0].texels[t]), expected[t], 1e-6))
        << "texel " << t << ": " << texture->levels[0].texels[t].r;
  const auto mask = load_alpha_mask(exr, AlphaSource::AlphaOnly, error);
  ASSERT_NE(mask, nullptr) << error;
  EXPECT_EQ(mask->values, (std::vector<float>{0.5f, 0.25f, 1.0f}));
}

class TextureFiles : public test::QuadFiles {
 protected:
  Scene load_quad(const std::string& texture_line) {
    return load_obj_quad(texture_line, "0.5 0.25 0.125");
  }
  // The only warning names the file, and the quad keeps its Kd untextured.
  void expect_one_warning_and_kd(const Scene& s, const std::string& file) const {
    ASSERT_EQ(diagnostics.warnings().size(), 1u) << warnings_of(diagnostics);
    const Diagnostic w = diagnostics.warnings()[0];
    EXPECT_NE((w.where + w.message).find(file), std::string::npos) << w.where << ": " << w.message;
    EXPECT_EQ(s.materials.at(0).texture, nullptr);
    EXPECT_EQ(s.materials.at(0).albedo, glm::vec3(0.5f, 0.25f, 0.125f));
  }
};

TEST_F(TextureFiles, NameInOtherLetterCaseIsFound) {
  fs::copy_file(kFloorScene / "checker.png", dir / "Checker.PNG");
  const Scene s = load_quad("map_Kd CHECKER.png");
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  EXPECT_NE(s.materials.at(0).texture, nullptr);
}

TEST_F(TextureFiles, MissingTextureWarnsOnceNamingItAndFallsBackToKd) {
  expect_one_warning_and_kd(load_quad("map_Kd nowhere.png"), "nowhere.png");
}

TEST_F(TextureFiles, UnreadableTextureWarnsOnceNamingItAndFallsBackToKd) {
  write("broken.png", "\x89PNG\r\n\x1a\nthis is not an image");
  expect_one_warning_and_kd(load_quad("map_Kd broken.png"), "broken.png");
}

TEST(TexturesSponza, EveryTexturedMaterialReadsItsTexture) {
  if (!fs::exists(kSponza)) GTEST_SKIP() << "no " << kSponza;
  Diagnostics d;
  const Scene s = SceneLoader(d).load(kSponza);
  std::size_t textured = 0;
  for (const Material& m : s.materials) textured += m.texture ? 1 : 0;
  // 20 materials in use, all but sp_01_stub_baza_ with a map_Kd; the mtl
  // names them in other letter case than the files.
  EXPECT_EQ(textured, 19u);
  for (const Diagnostic& w : d.warnings()) {
    EXPECT_EQ(w.message.find("texture"), std::string::npos) << w.message;
    EXPECT_EQ(w.message.find("ignored"), std::string::npos) << w.message;
  }
}

}  // namespace
}  // namespace bounce
