// A lit mesh with its scene's materials as binary glTF, read back with Assimp:
// two quads sharing an edge, one textured from a TIFF (not a format glTF
// embeds, so the writer encodes it as PNG), one textured from the same TIFF
// and cut by a separate 2 x 1 mask. Checked by hand:
//   - the shared edge's vertices are copied into both primitives;
//   - the TIFF's 8-bit sRGB codes come back from the embedded PNG unchanged;
//   - the masked image's alpha is the mask looked up bilinearly (wrapping) at
//     the texel centres: 0.25, 0.25, 0.75, 0.75 along a row;
//   - COLOR_0 is the radiosity over the material's albedo times the exposure;
//   - texture coordinates are the scene's, v up again after Assimp's flip.
#include <OpenImageIO/imageio.h>
#include <assimp/GltfMaterial.h>
#include <assimp/material.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <assimp/Importer.hpp>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "runtime/lit_scene_glb.h"
#include "scene/alpha_mask.h"
#include "scene/texture.h"
#include "scratch_dir.h"

namespace bounce {
namespace {

// A 4 x 2 RGB image of distinct 8-bit codes, row-major, top row first.
std::vector<std::uint8_t> codes() {
  std::vector<std::uint8_t> c;
  for (int i = 0; i < 24; ++i) c.push_back(static_cast<std::uint8_t>(10 * i + 7));
  return c;
}

std::filesystem::path write_tiff(const test::ScratchDir& dir) {
  const std::filesystem::path path = dir / "colour.tif";
  auto out = OIIO::ImageOutput::create(path.string());
  EXPECT_TRUE(out);
  const OIIO::ImageSpec spec(4, 2, 3, OIIO::TypeDesc::UINT8);
  const std::vector<std::uint8_t> c = codes();
  EXPECT_TRUE(out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, c.data()) &&
              out->close());
  return path;
}

struct Fixture {
  Scene scene;
  LitMesh mesh;
};

// Quad A (x in [0, 1]) textured, quad B (x in [1, 2]) textured and masked,
// sharing the edge x = 1; texture coordinates u = x - left edge, v = z.
Fixture make_fixture(const std::filesystem::path& tiff) {
  Fixture f;
  Scene& s = f.scene;
  std::string error;
  const auto texture = load_texture(tiff, error);
  EXPECT_NE(texture, nullptr) << error;
  auto mask = std::make_shared<AlphaMask>();
  mask->width = 2;
  mask->height = 1;
  mask->values = {0.0f, 1.0f};
  Material a;
  a.name = "tiled";
  a.texture = texture;
  a.texture_factor = glm::vec3(0.5f, 1.0f, 1.0f);
  a.albedo = a.texture_factor * texture->mean;
  Material b = a;
  b.name = "cut";
  b.alpha_mask = mask;
  b.alpha_cutoff = 0.3f;
  b.alpha_factor = 0.9f;
  s.materials = {a, b};
  s.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, {2, 0, 0}, {2, 0, 1}};
  s.triangles = {{0, 2, 1}, {0, 3, 2}, {1, 5, 4}, {1, 2, 5}};
  s.triangle_material = {0, 0, 1, 1};
  s.triangle_mesh = {0, 0, 0, 0};
  s.meshes.push_back({"quads", "", 0, 4});
  const auto uv = [&](std::uint32_t v, float left) {
    return glm::vec2(s.positions[v].x - left, s.positions[v].z);
  };
  for (std::size_t t = 0; t < 4; ++t) {
    const float left = t < 2 ? 0.0f : 1.0f;
    s.triangle_uv.push_back(
        {uv(s.triangles[t][0], left), uv(s.triangles[t][1], left), uv(s.triangles[t][2], left)});
  }
  // The lit mesh: the scene's own vertices, one shared edge.
  f.mesh.positions = s.positions;
  f.mesh.normals.assign(6, glm::vec3(0, 1, 0));
  f.mesh.radiosity = {{0.1f, 0.2f, 0.3f},  {0.2f, 0.2f, 0.2f}, {0.3f, 0.1f, 0.1f},
                      {0.05f, 0.1f, 0.2f}, {0.4f, 0.3f, 0.2f}, {0.0f, 0.0f, 0.0f}};
  f.mesh.triangles = s.triangles;
  f.mesh.source_triangle = {0, 1, 2, 3};
  return f;
}

std::vector<std::uint8_t> decoded_codes(const aiTexture* t, const test::ScratchDir& dir,
                                        int& channels) {
  EXPECT_EQ(t->mHeight, 0u);
  EXPECT_TRUE(t->CheckFormat("png")) << t->achFormatHint;
  const std::filesystem::path file = dir / "embedded.png";
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(t->pcData), t->mWidth);
  // As stored: OpenImageIO would otherwise multiply the colour by alpha.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(file.string(), &config);
  EXPECT_TRUE(in);
  if (!in) return {};
  channels = in->spec().nchannels;
  std::vector<std::uint8_t> out(
      static_cast<std::size_t>(in->spec().width * in->spec().height * channels));
  EXPECT_TRUE(in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, out.data()));
  return out;
}

TEST(LitSceneGlb, TexturesMasksSeamsAndLightWithoutAlbedo) {
  const test::ScratchDir dir("bounce-lit-glb");
  const Fixture f = make_fixture(write_tiff(dir));
  const float exposure = write_lit_scene_glb(dir / "lit.glb", f.scene, f.mesh, "quads");
  ASSERT_GT(exposure, 0.0f);

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile((dir / "lit.glb").string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 2u) << "one primitive per material, none for the unused plain one";
  std::size_t vertices = 0;
  const std::vector<std::uint8_t> want = codes();
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    const aiMesh* mesh = scene->mMeshes[i];
    const aiMaterial* material = scene->mMaterials[mesh->mMaterialIndex];
    const std::string name = material->GetName().C_Str();
    ASSERT_TRUE(name == "tiled" || name == "cut") << name;
    const bool cut = name == "cut";
    const Material& m = f.scene.materials[cut ? 1 : 0];
    vertices += mesh->mNumVertices;

    aiString path;
    ASSERT_EQ(material->GetTexture(aiTextureType_DIFFUSE, 0, &path), aiReturn_SUCCESS);
    int channels = 0;
    const std::vector<std::uint8_t> got =
        decoded_codes(scene->GetEmbeddedTexture(path.C_Str()), dir, channels);
    ASSERT_EQ(channels, cut ? 4 : 3);
    ASSERT_EQ(got.size(), 8u * static_cast<std::size_t>(channels));
    const std::uint8_t alpha[4] = {64, 64, 191, 191};
    for (std::size_t p = 0; p < 8; ++p) {
      for (std::size_t c = 0; c < 3; ++c)
        EXPECT_EQ(got[p * static_cast<std::size_t>(channels) + c], want[p * 3 + c])
            << name << " texel " << p << " channel " << c;
      if (cut) {
        EXPECT_EQ(got[p * 4 + 3], alpha[p % 4]) << "texel " << p;
      }
    }
    aiString mode;
    const bool has_mode = material->Get(AI_MATKEY_GLTF_ALPHAMODE, mode) == aiReturn_SUCCESS;
    EXPECT_EQ(has_mode ? std::string(mode.C_Str()) : "OPAQUE", cut ? "MASK" : "OPAQUE");
    aiColor4D factor;
    ASSERT_EQ(material->Get(AI_MATKEY_BASE_COLOR, factor), aiReturn_SUCCESS);
    EXPECT_FLOAT_EQ(factor.r, 0.5f);
    EXPECT_FLOAT_EQ(factor.a, cut ? 0.9f : 1.0f);

    ASSERT_TRUE(mesh->HasTextureCoords(0));
    ASSERT_TRUE(mesh->HasVertexColors(0));
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D p = mesh->mVertices[v];
      std::size_t source = 0;
      while (source < 6 && glm::length(f.scene.positions[source] - glm::vec3(p.x, p.y, p.z)) > 0)
        ++source;
      ASSERT_LT(source, 6u);
      EXPECT_NEAR(mesh->mTextureCoords[0][v].x, p.x - (cut ? 1.0f : 0.0f), 1e-6f);
      EXPECT_NEAR(mesh->mTextureCoords[0][v].y, p.z, 1e-6f);
      const aiColor4D colour = mesh->mColors[0][v];
      const float got_colour[3] = {colour.r, colour.g, colour.b};
      for (int c = 0; c < 3; ++c) {
        const float light = f.mesh.radiosity[source][c] / m.albedo[c];
        EXPECT_NEAR(got_colour[c], std::min(light * exposure, 1.0f), 1e-6f)
            << name << " vertex " << v << " channel " << c;
      }
    }
  }
  EXPECT_EQ(vertices, 8u) << "the shared edge's two vertices are in both primitives";
}

}  // namespace
}  // namespace bounce
