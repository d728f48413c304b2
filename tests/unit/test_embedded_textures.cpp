// Images embedded in glTF files (a .glb's bufferViews, a .gltf's data URIs)
// are read as files are. The round trip: the shipped textured-floor scene
// (an 8 x 8 checker of two known sRGB colours on the floor, a fence cut by
// an 8 x 8 mask of which half is solid) written as a .glb by our own writer,
// which embeds the checker's PNG byte for byte and the mask as a PNG's
// alpha, then loaded back as a scene: the floor's albedo and sample albedo
// are the checker's mean, its squares the two colours, the fence keeps its
// holes, and writing it again embeds the same bytes. And the other slots
// (emissive texture, normal map) from data URIs; a corrupt embedded image
// or an index the file does not embed: one warning naming the file and the
// material, the factor instead; raw embedded texels read as the PNG of
// them would.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "base/diagnostics.h"
#include "gltf_quad.h"
#include "io/glb_writer.h"
#include "patches/samples.h"
#include "quad_files.h"
#include "raytrace/ray_tracer.h"
#include "runtime/glb_materials.h"
#include "scene/alpha_mask.h"
#include "scene/scene_loader.h"
#include "scene/texture.h"
#include "scratch_dir.h"
#include "textured_floor.h"
#include "voxel/voxelization.h"
#include "warnings_text.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

using test::colour_a;
using test::colour_b;
using test::kFloorScene;
using test::near;
using test::warnings_of;

std::string file_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::uint8_t> file_bytes(const fs::path& file) {
  const std::string text = file_text(file);
  return {text.begin(), text.end()};
}

const Material& material_named(const Scene& s, const std::string& name) {
  for (const Material& m : s.materials)
    if (m.name == name) return m;
  throw std::runtime_error("no material " + name);
}

// `scene` as a .glb through the writer `bounce` exports with: its materials
// (glb_materials: textures and masks embedded), one primitive per glTF
// material with every triangle's corners and texture coordinates, and light
// 1 everywhere at exposure 1, so that COLOR_0 (which the loader multiplies
// the albedo by) is 1. The albedo a lit file carries in COLOR_0 goes into
// the factor of the untextured materials instead (the plain material's
// white would be no valid albedo).
GlbMaterials write_as_glb(const Scene& scene, const fs::path& glb) {
  GlbMaterials materials = glb_materials(scene, std::vector<bool>(scene.materials.size(), true));
  GlbModel model;
  model.name = "round trip";
  model.images = materials.images;
  model.materials = materials.materials;
  model.materials[0].base_color = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const std::size_t g = materials.of_scene_material[i];
    if (g != 0 && !materials.textured[i])
      model.materials[g].base_color = glm::vec4(scene.materials[i].albedo, 1.0f);
  }
  model.primitives.resize(model.materials.size());
  for (std::size_t g = 0; g < model.primitives.size(); ++g) model.primitives[g].material = g;
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    const std::size_t g = materials.of_scene_material[scene.triangle_material[t]];
    GlbPrimitive& p = model.primitives[g];
    const glm::vec3 normal = glm::normalize(scene.triangle_cross(t));
    const auto first = static_cast<std::uint32_t>(p.positions.size());
    for (int c = 0; c < 3; ++c) {
      p.positions.push_back(scene.vertex(t, c));
      p.normals.push_back(normal);
      p.light.emplace_back(1.0f);
      p.radiance.emplace_back(1.0f);
      if (model.materials[g].base_color_image) {
        const glm::vec2 uv = scene.triangle_uv[t][static_cast<std::size_t>(c)];
        p.uv.emplace_back(uv.x, 1.0f - uv.y);  // glTF's v runs down
      }
    }
    p.triangles.emplace_back(first, first + 1, first + 2);
  }
  std::erase_if(model.primitives, [](const GlbPrimitive& p) { return p.triangles.empty(); });
  write_glb(glb, model);
  return materials;
}

// The image glb_materials embeds for scene material `name`.
const GlbImage& image_of(const Scene& s, const GlbMaterials& g, const std::string& name) {
  for (std::size_t i = 0; i < s.materials.size(); ++i)
    if (s.materials[i].name == name) {
      const GlbMaterial& material = g.materials.at(g.of_scene_material[i]);
      if (!material.base_color_image) break;
      return g.images.at(*material.base_color_image);
    }
  throw std::runtime_error("no image for material " + name);
}

class EmbeddedGlb : public ::testing::Test {
 protected:
  test::ScratchDir dir{"bounce-embedded-glb"};
  Diagnostics diagnostics;
  Scene files;   // the scene as shipped, its images files
  Scene loaded;  // the scene written as a .glb and loaded back
  GlbMaterials written;

  void SetUp() override {
    Diagnostics d;
    files = SceneLoader(d).load(kFloorScene);
    ASSERT_TRUE(d.warnings().empty()) << warnings_of(d);
    written = write_as_glb(files, dir / "floor.glb");
    loaded = SceneLoader(diagnostics).load(dir / "floor.glb");
  }
};

TEST_F(EmbeddedGlb, FloorReadsTheEmbeddedCheckerWithoutWarnings) {
  // The writer embedded the checker's own file bytes.
  EXPECT_EQ(image_of(files, written, "floor").bytes, file_bytes(kFloorScene / "checker.png"));
  // Nothing about embedded images (or anything else) to warn about.
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  const Material& floor = material_named(loaded, "floor");
  ASSERT_NE(floor.texture, nullptr);
  ASSERT_TRUE(floor.texture->source.is_embedded());
  EXPECT_NE(floor.texture->source.name().find("floor.glb#texture "), std::string::npos)
      << floor.texture->source.name();
  EXPECT_EQ(floor.texture->levels.front().width, 64);
  // Half the squares of each colour: the flat albedo is their mean.
  EXPECT_TRUE(near(glm::dvec3(floor.albedo), 0.5 * (colour_a() + colour_b()), 2e-3))
      << floor.albedo.x << " " << floor.albedo.y << " " << floor.albedo.z;
  // What the reference and camera pictures look up: each square's centre is
  // one colour or the other, alternating (32 of each).
  ASSERT_EQ(loaded.triangle_uv.size(), loaded.triangle_count());
  const RayTracer tracer(loaded);
  int a = 0, b = 0;
  bool first_is_a = false;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) {
      const glm::vec3 p(-1.0f + (static_cast<float>(i) + 0.5f) / 4.0f, 0.0f,
                        -1.0f + (static_cast<float>(j) + 0.5f) / 4.0f);
      const Hit hit = tracer.intersect(p + glm::vec3(0.0f, 0.5f, 0.0f), {0.0f, -1.0f, 0.0f});
      ASSERT_TRUE(hit.hit);
      ASSERT_EQ(loaded.material_of(hit.triangle).name, "floor");
      const glm::dvec3 albedo(loaded.albedo_at(hit.triangle, p));
      const bool is_a = near(albedo, colour_a(), 2e-3), is_b = near(albedo, colour_b(), 2e-3);
      EXPECT_TRUE(is_a || is_b) << "square " << i << "," << j;
      (is_a ? a : b) += 1;
      if (i == 0 && j == 0) first_is_a = is_a;
      EXPECT_EQ(is_a, first_is_a == ((i + j) % 2 == 0)) << "square " << i << "," << j;
    }
  EXPECT_EQ(a, 32);
  EXPECT_EQ(b, 32);
}

TEST_F(EmbeddedGlb, SampleAlbedoIsTheCheckersMean) {
  test::expect_floor_samples_carry_the_checker(loaded);
}

TEST_F(EmbeddedGlb, FenceKeepsItsHoles) {
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  const Material& fence = material_named(loaded, "fence");
  ASSERT_NE(fence.alpha_mask, nullptr);
  EXPECT_TRUE(fence.alpha_mask->source.is_embedded());
  EXPECT_EQ(fence.alpha_cutoff, 0.5f);
  // fence-mask.png: 8 x 8, alpha 255 where (x / 2 + y / 2) is even, else 0;
  // the writer looked the mask up at its own texel centres.
  ASSERT_EQ(fence.alpha_mask->width, 8);
  ASSERT_EQ(fence.alpha_mask->height, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      EXPECT_EQ(fence.alpha_mask->values[static_cast<std::size_t>(y * 8 + x)],
                (x / 2 + y / 2) % 2 == 0 ? 1.0f : 0.0f)
          << x << "," << y;
  double fence_area = 0.0;
  for (std::size_t t = 0; t < loaded.triangle_count(); ++t) {
    EXPECT_EQ(loaded.masked(t), &loaded.material_of(t) == &fence);
    if (&loaded.material_of(t) == &fence) fence_area += loaded.triangle_area(t);
  }
  // Samples stand on the solid half only.
  const RayTracer tracer(loaded);
  const Voxelization vox = voxelize(loaded, VoxelGrid(loaded.bounds(), 8));
  const SampleSet set = generate_samples(loaded, tracer, vox, SamplingSettings{});
  double solid = 0.0;
  for (const Sample& x : set.samples)
    if (loaded.material_of(x.triangle).name == "fence") solid += x.area;
  ASSERT_GT(fence_area, 0.0);
  EXPECT_NEAR(solid / fence_area, 0.5, 0.01);
}

// The fence is written as a white image holding the mask as alpha, with the
// OBJ's Kd as its factor; loaded back, its albedo (flat and every sample's)
// is the OBJ's: the white of the solid texels times the factor, the holes
// counting nowhere.
TEST_F(EmbeddedGlb, FenceAlbedoIsTheObjs) {
  const Material& obj = material_named(files, "fence");
  const Material& glb = material_named(loaded, "fence");
  ASSERT_EQ(obj.texture, nullptr);
  ASSERT_NE(glb.texture, nullptr);
  EXPECT_TRUE(near(glm::dvec3(glb.albedo), glm::dvec3(obj.albedo), 1e-6))
      << glb.albedo.x << " " << glb.albedo.y << " " << glb.albedo.z;
  int fence_samples = 0;
  for (const Sample& x : test::textured_samples(loaded).samples) {
    if (&loaded.material_of(x.triangle) != &glb) continue;
    ++fence_samples;
    EXPECT_TRUE(near(glm::dvec3(x.albedo), glm::dvec3(obj.albedo), 1e-5))
        << x.albedo.x << " " << x.albedo.y << " " << x.albedo.z;
  }
  EXPECT_GT(fence_samples, 0);
}

TEST_F(EmbeddedGlb, WritingItAgainEmbedsTheSameBytes) {
  const GlbMaterials again =
      glb_materials(loaded, std::vector<bool>(loaded.materials.size(), true));
  EXPECT_EQ(image_of(loaded, again, "floor").bytes, file_bytes(kFloorScene / "checker.png"));
  // The fence's image holds its mask as alpha already: copied, not encoded anew.
  EXPECT_EQ(image_of(loaded, again, "fence").bytes, image_of(files, written, "fence").bytes);
}

// The checker's PNG inside the .glb with bytes of its compressed data
// overwritten: the floor falls back to its factor, with one warning naming
// the file and the material.
TEST_F(EmbeddedGlb, CorruptEmbeddedImageWarnsOnceAndFallsBackToTheFactor) {
  std::string glb = file_text(dir / "floor.glb");
  const std::vector<std::uint8_t> png = file_bytes(kFloorScene / "checker.png");
  const std::size_t at = glb.find(std::string(png.begin(), png.end()));
  ASSERT_NE(at, std::string::npos) << "the checker's bytes are in the file";
  const std::size_t idat = glb.find("IDAT", at);
  ASSERT_NE(idat, std::string::npos);
  for (std::size_t i = idat + 6; i < idat + 40; ++i) glb[i] = static_cast<char>(glb[i] ^ 0x5a);
  std::ofstream(dir / "corrupt.glb", std::ios::binary) << glb;

  Diagnostics d;
  const Scene s = SceneLoader(d).load(dir / "corrupt.glb");
  ASSERT_EQ(d.warnings().size(), 1u) << warnings_of(d);
  const Diagnostic w = d.warnings()[0];
  EXPECT_NE((w.where + w.message).find("corrupt.glb"), std::string::npos) << w.where << w.message;
  EXPECT_NE(w.message.find("'floor'"), std::string::npos) << w.message;
  EXPECT_EQ(w.message.find('\n'), std::string::npos) << "one line: " << w.message;
  const Material& floor = material_named(s, "floor");
  EXPECT_EQ(floor.texture, nullptr);
  EXPECT_TRUE(near(glm::dvec3(floor.albedo), glm::dvec3(0.9), 1e-6))
      << floor.albedo.x << " " << floor.albedo.y << " " << floor.albedo.z;
  // The other images are unharmed.
  EXPECT_NE(material_named(s, "fence").alpha_mask, nullptr);
}

std::string data_uri(const fs::path& png) {
  return "data:image/png;base64," + test::base64(file_text(png));
}

// The glTF quad of tests/unit/gltf_quad.h with its images as data URIs.
class EmbeddedGltf : public test::QuadFiles {
 protected:
  Scene load_gltf_quad(const std::string& image, const std::string& material,
                       const std::string& factor) {
    write("quad.gltf", test::gltf_quad(image, material, factor));
    return SceneLoader(diagnostics).load(dir / "quad.gltf");
  }
};

// The normal map of the textured-floor scene as the quad's base colour,
// emissive texture and normal map at once: each reads what the file gives.
TEST_F(EmbeddedGltf, EverySlotReadsItsDataUriAsTheFile) {
  const fs::path ridges = kFloorScene / "wall-ridges.png";
  const Scene s = load_gltf_quad(data_uri(ridges),
                                 R"(, "emissiveTexture": {"index": 0}, "emissiveFactor": [2, 2, 2],
                                 "normalTexture": {"index": 0, "scale": 0.5})",
                                 "[0.5, 0.5, 0.5, 1]");
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  std::string error;
  const auto colour = load_texture(ridges, error);
  const auto directions = load_texture(ridges, error, TexelKind::Direction);
  ASSERT_NE(colour, nullptr) << error;
  ASSERT_NE(directions, nullptr) << error;
  const Material& m = s.materials.at(0);
  ASSERT_NE(m.texture, nullptr);
  ASSERT_NE(m.emission_texture, nullptr);
  ASSERT_NE(m.normal_map, nullptr);
  for (const auto* t : {m.texture.get(), m.emission_texture.get(), m.normal_map.get()})
    EXPECT_TRUE(t->source.is_embedded()) << t->source.name();
  EXPECT_EQ(m.texture->levels.front().texels, colour->levels.front().texels);
  EXPECT_EQ(m.emission_texture->levels.front().texels, colour->levels.front().texels);
  EXPECT_EQ(m.normal_map->levels.front().texels, directions->levels.front().texels);
  EXPECT_EQ(m.normal_scale, 0.5f);
  EXPECT_EQ(m.albedo, 0.5f * colour->mean);
  EXPECT_EQ(m.emission, 2.0f * colour->mean);
}

TEST_F(EmbeddedGltf, CorruptDataUriWarnsOnceNamingFileAndMaterialAndFallsBack) {
  const std::string broken = "\x89PNG\r\n\x1a\nthis is not an image";
  const Scene s = load_gltf_quad("data:image/png;base64," + test::base64(broken),
                                 R"(, "alphaMode": "MASK")", "[0.5, 0.25, 0.125, 1]");
  ASSERT_EQ(diagnostics.warnings().size(), 1u) << warnings_of(diagnostics);
  const Diagnostic w = diagnostics.warnings()[0];
  EXPECT_NE((w.where + w.message).find("quad.gltf"), std::string::npos) << w.where << w.message;
  EXPECT_NE(w.message.find("'leaf'"), std::string::npos) << w.message;
  EXPECT_NE(w.message.find("cannot read this texture"), std::string::npos) << w.message;
  const Material& m = s.materials.at(0);
  EXPECT_EQ(m.texture, nullptr);
  EXPECT_EQ(m.albedo, glm::vec3(0.5f, 0.25f, 0.125f));
  EXPECT_FALSE(s.has_masks()) << "the mask is the image's alpha: the quad stays whole";
}

// An image named "*7" (here a URI that Assimp passes on as the texture's
// name) stands for embedded image 7, which the file does not hold.
TEST_F(EmbeddedGltf, IndexTheFileDoesNotEmbedWarnsOnceNamingFileAndMaterial) {
  const Scene s = load_gltf_quad("*7", "", "[0.5, 0.25, 0.125, 1]");
  ASSERT_EQ(diagnostics.warnings().size(), 1u) << warnings_of(diagnostics);
  const Diagnostic w = diagnostics.warnings()[0];
  EXPECT_NE(w.where.find("quad.gltf"), std::string::npos) << w.where;
  EXPECT_NE(w.message.find("'leaf'"), std::string::npos) << w.message;
  EXPECT_NE(w.message.find("'*7'"), std::string::npos) << w.message;
  EXPECT_EQ(s.materials.at(0).texture, nullptr);
  EXPECT_EQ(s.materials.at(0).albedo, glm::vec3(0.5f, 0.25f, 0.125f));
}

// Some formats embed raw RGBA8 texels instead of an image file: they read
// as the same texels written to a PNG file do (sRGB colour, as stored
// whatever the alpha), alpha is linear.
TEST(EmbeddedImages, RawTexelsReadAsTheirPngDoes) {
  const std::vector<std::uint8_t> rgba = {255, 0, 0, 255, 10,  128, 250, 0,
                                          0,   0, 0, 128, 200, 100, 30,  255};
  const test::ScratchDir dir("bounce-raw-texels");
  const fs::path png = dir / "texels.png";
  auto out = OIIO::ImageOutput::create(png.string());
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(2, 2, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // the bytes as given, not divided by alpha
  ASSERT_TRUE(out->open(png.string(), spec) &&
              out->write_image(OIIO::TypeDesc::UINT8, rgba.data()) && out->close());

  auto raw = std::make_shared<EmbeddedImage>();
  raw->name = "model.mdl#texture 0";
  raw->bytes = rgba;
  raw->raw_width = raw->raw_height = 2;
  const ImageSource source(raw);
  std::string error;
  const auto from_raw = load_texture(source, error);
  ASSERT_NE(from_raw, nullptr) << error;
  const auto from_png = load_texture(png, error);
  ASSERT_NE(from_png, nullptr) << error;
  EXPECT_EQ(from_raw->source.name(), "model.mdl#texture 0");
  for (std::size_t t = 0; t < 4; ++t)
    for (glm::length_t c = 0; c < 3; ++c)
      EXPECT_NEAR(from_raw->levels[0].texels[t][c], from_png->levels[0].texels[t][c], 1e-6f)
          << "texel " << t << " channel " << c;
  EXPECT_TRUE(near(glm::dvec3(from_raw->levels[0].texels[1]),
                   glm::dvec3(test::decode(10), test::decode(128), test::decode(250)), 1e-6));
  const auto mask = load_alpha_mask(source, AlphaSource::AlphaOnly, error);
  ASSERT_NE(mask, nullptr) << error;
  EXPECT_EQ(mask->values, (std::vector<float>{1.0f, 0.0f, 128.0f / 255.0f, 1.0f}));

  // Texels that do not fill the stated size: an error, no texture.
  raw->raw_height = 3;
  EXPECT_EQ(load_texture(ImageSource(raw), error), nullptr);
  EXPECT_NE(error.find("2 x 3"), std::string::npos) << error;
}

}  // namespace
}  // namespace bounce
