// The lit textured scene as binary glTF (`bounce bake --export-glb`, and
// `bounce solve`'s lit.glb), read back with Assimp, a glTF reader independent
// of the writer. The textured-floor scene has a floor mapped once onto an
// 8 x 8 checker (u = (x + 1) / 2, v = (1 - z) / 2, v up), a plain wall and a
// fence cut by an alpha mask. Checked against the PLY `bounce solve` writes of
// the same light:
//   - the floor's vertex colours are its light without the albedo (the PLY's
//     radiosity over Kd x the checker's mean, decoded here from the two sRGB
//     colours), the plain ones the radiosity, both times the file's exposure
//     and clamped, within 1/255;
//   - the floor has a base colour texture whose embedded image decodes to
//     the checker's pixels, and texture coordinates from its placement;
//   - the fence's material is alphaMode MASK, cutoff 0.5, its image's alpha
//     the mask's.
// And the batch: two scenes and a broken one give two files, one error line
// naming the broken scene, and exit code 2.
#include <assimp/GltfMaterial.h>
#include <assimp/material.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>

#include "cli_harness.h"
#include "ply_vertices.h"
#include "scene/texture.h"

namespace bounce::itest {
namespace {

double decode(int byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// The floor's mean albedo: Kd 0.9 times the mean of the checker's two colours.
glm::dvec3 floor_albedo() {
  return 0.45 * (glm::dvec3(decode(224), decode(96), decode(64)) +
                 glm::dvec3(decode(48), decode(128), decode(192)));
}

const std::vector<std::string> kSmall = {
    "--voxel", "4",     "--closure-rays", "64",     "--final-gather-rays", "32",
    "--codec", "dense", "--no-pictures",  "--quiet"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// asset.extras.exposure from the file's JSON chunk (Assimp does not expose it).
double exposure_of(const fs::path& glb) {
  const std::string bytes = read_text(glb);
  EXPECT_GT(bytes.size(), 20u);
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return parse_json(bytes.substr(20, length))["asset"]["extras"]["exposure"].get<double>();
}

// The decoded pixels of an embedded image, through a file OpenImageIO reads.
ImagePixels embedded_pixels(const aiScene* scene, const aiMaterial* material,
                            const fs::path& scratch) {
  aiString path;
  EXPECT_EQ(material->GetTexture(aiTextureType_DIFFUSE, 0, &path), aiReturn_SUCCESS);
  const aiTexture* texture = scene->GetEmbeddedTexture(path.C_Str());
  EXPECT_NE(texture, nullptr) << path.C_Str();
  if (texture == nullptr) return {};
  EXPECT_EQ(texture->mHeight, 0u) << "an encoded file, not raw texels";
  EXPECT_TRUE(texture->CheckFormat("png") || texture->CheckFormat("jpg"));
  const fs::path file = scratch / (std::string("embedded.") + texture->achFormatHint);
  write_text(file, std::string(reinterpret_cast<const char*>(texture->pcData), texture->mWidth));
  std::string error;
  const std::optional<ImagePixels> pixels = read_image_pixels(file, error);
  EXPECT_TRUE(pixels.has_value()) << error;
  return pixels.value_or(ImagePixels{});
}

ImagePixels file_pixels(const fs::path& file) {
  std::string error;
  const std::optional<ImagePixels> pixels = read_image_pixels(file, error);
  EXPECT_TRUE(pixels.has_value()) << file << ": " << error;
  return pixels.value_or(ImagePixels{});
}

// Both images have the same size, and the same values in `channels`.
void expect_same_pixels(const ImagePixels& got, const ImagePixels& want,
                        const std::vector<std::size_t>& channels) {
  ASSERT_EQ(got.width, want.width);
  ASSERT_EQ(got.height, want.height);
  const auto got_channels = static_cast<std::size_t>(got.channels);
  const auto want_channels = static_cast<std::size_t>(want.channels);
  for (const std::size_t c : channels) {
    ASSERT_LT(c, got_channels);
    ASSERT_LT(c, want_channels);
  }
  for (std::size_t p = 0; p < static_cast<std::size_t>(want.width * want.height); ++p)
    for (const std::size_t c : channels)
      ASSERT_NEAR(got.pixels[p * got_channels + c], want.pixels[p * want_channels + c], 1e-6)
          << "texel " << p << " channel " << c;
}

const aiMaterial* material_named(const aiScene* scene, const std::string& name) {
  for (unsigned m = 0; m < scene->mNumMaterials; ++m)
    if (scene->mMaterials[m]->GetName().C_Str() == name) return scene->mMaterials[m];
  return nullptr;
}

// The PLY row with the vertex's position and normal (the lit mesh's vertices
// are unique by both; the glTF copies them at seams).
std::size_t ply_row(const PlyVertices& ply, const aiMesh* mesh, unsigned v) {
  const std::size_t x = ply.column("x"), nx = ply.column("nx");
  std::size_t best = 0;
  double best_d = std::numeric_limits<double>::max();
  for (std::size_t r = 0; r < ply.rows.size(); ++r) {
    double d = 0.0;
    for (unsigned c = 0; c < 3; ++c) {
      d += std::abs(ply.rows[r][x + c] - mesh->mVertices[v][c]);
      d += std::abs(ply.rows[r][nx + c] - mesh->mNormals[v][c]);
    }
    if (d < best_d) best_d = d, best = r;
  }
  EXPECT_LT(best_d, 1e-4) << "no PLY vertex at glTF vertex " << v;
  return best;
}

void check_textured_floor_glb(const fs::path& glb, const PlyVertices& ply,
                              const fs::path& scratch) {
  SCOPED_TRACE(glb.string());
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(glb.string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  const double exposure = exposure_of(glb);
  ASSERT_GT(exposure, 0.0);

  const aiMaterial* floor = material_named(scene, "floor");
  const aiMaterial* fence = material_named(scene, "fence");
  ASSERT_NE(floor, nullptr);
  ASSERT_NE(fence, nullptr);

  // The floor's texture is the checker, pixel for pixel.
  const ImagePixels checker = file_pixels(kScenes / "textured-floor" / "checker.png");
  expect_same_pixels(embedded_pixels(scene, floor, scratch), checker, {0, 1, 2});
  aiColor4D factor;
  ASSERT_EQ(floor->Get(AI_MATKEY_BASE_COLOR, factor), aiReturn_SUCCESS);
  EXPECT_NEAR(factor.r, 0.9f, 1e-6f) << "Kd";

  // The fence is cut by its mask: alphaMode MASK, its image's alpha the mask's.
  aiString mode;
  ASSERT_EQ(fence->Get(AI_MATKEY_GLTF_ALPHAMODE, mode), aiReturn_SUCCESS);
  EXPECT_STREQ(mode.C_Str(), "MASK");
  float cutoff = 0.0f;
  ASSERT_EQ(fence->Get(AI_MATKEY_GLTF_ALPHACUTOFF, cutoff), aiReturn_SUCCESS);
  EXPECT_FLOAT_EQ(cutoff, 0.5f);
  const ImagePixels mask = file_pixels(kScenes / "textured-floor" / "fence-mask.png");
  expect_same_pixels(embedded_pixels(scene, fence, scratch), mask, {3});
  aiString floor_mode;
  if (floor->Get(AI_MATKEY_GLTF_ALPHAMODE, floor_mode) == aiReturn_SUCCESS) {
    EXPECT_STREQ(floor_mode.C_Str(), "OPAQUE");
  }

  const glm::dvec3 albedo = floor_albedo();
  const std::size_t r = ply.column("radiance_r");
  std::size_t floor_vertices = 0, lit = 0;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    const aiMesh* mesh = scene->mMeshes[i];
    const bool is_floor = scene->mMaterials[mesh->mMaterialIndex] == floor;
    ASSERT_TRUE(mesh->HasVertexColors(0));
    ASSERT_TRUE(mesh->HasNormals());
    if (is_floor) {
      ASSERT_TRUE(mesh->HasTextureCoords(0));
    }
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const std::size_t row = ply_row(ply, mesh, v);
      const aiColor4D colour = mesh->mColors[0][v];
      const float got[3] = {colour.r, colour.g, colour.b};
      for (unsigned c = 0; c < 3; ++c) {
        const double light = ply.rows[row][r + c] / (is_floor ? albedo[static_cast<int>(c)] : 1.0);
        const double want = std::clamp(light * exposure, 0.0, 1.0);
        ASSERT_NEAR(got[c], want, 1.0 / 255.0)
            << "mesh " << i << " vertex " << v << " channel " << c;
      }
      if (!is_floor) continue;
      ++floor_vertices;
      lit += colour.r + colour.g + colour.b > 0.0f ? 1 : 0;
      const aiVector3D uv = mesh->mTextureCoords[0][v];
      EXPECT_NEAR(uv.x, (mesh->mVertices[v].x + 1.0f) / 2.0f, 1e-5f) << "vertex " << v;
      EXPECT_NEAR(uv.y, (1.0f - mesh->mVertices[v].z) / 2.0f, 1e-5f) << "vertex " << v;
    }
  }
  EXPECT_GT(floor_vertices, 8u) << "the floor is refined";
  EXPECT_GT(lit, floor_vertices / 2) << "the sun lights the floor";
}

TEST(ExportGlb, TexturedFloorCarriesTexturesUvsMasksAndTheLight) {
  TempDir tmp;
  const fs::path bake = tmp.path() / "bakes" / "floor";
  const RunResult r =
      run(with({"bake", scene("textured-floor"), "--export-glb", "--out", bake.string()}, kSmall),
          tmp.path());
  ASSERT_EQ(r.exit_code, 0) << r;
  const fs::path glb = tmp.path() / "bakes" / "floor.glb";
  ASSERT_TRUE(fs::exists(glb)) << r;
  const RunResult s = run(
      {"solve", bake.string(), "--no-images", "--quiet", "--out", (tmp.path() / "solve").string()},
      tmp.path());
  ASSERT_EQ(s.exit_code, 0) << s;
  const PlyVertices ply = read_ply_vertices(tmp.path() / "solve" / "lit.ply");
  check_textured_floor_glb(glb, ply, tmp.path());
  check_textured_floor_glb(tmp.path() / "solve" / "lit.glb", ply, tmp.path());
}

TEST(ExportGlb, BatchExportsEachSceneAndNamesTheBrokenOne) {
  TempDir tmp;
  const fs::path scenes = tmp.path() / "scenes";
  fs::create_directories(scenes);
  for (const char* name : {"textured-floor", "parallel-squares"})
    fs::copy(kScenes / name, scenes / name, fs::copy_options::recursive);
  fs::create_directories(scenes / "broken");
  write_text(scenes / "broken" / "scene.json", "{ \"meshes\": [ { \"file\": ");
  const fs::path out = tmp.path() / "bakes";
  const RunResult r =
      run(with({"bake", (scenes / "*").string(), "--export-glb", "--out", out.string(), "--json"},
               kSmall),
          tmp.path(), 120.0);
  EXPECT_EQ(r.exit_code, 2) << r;
  const std::vector<std::string> errors = lines_starting_with(r.err, "bounce: error");
  ASSERT_EQ(errors.size(), 1u) << r;
  EXPECT_TRUE(contains(errors[0], (scenes / "broken" / "scene.json").string())) << errors[0];
  const json summary = parse_json(r.out);
  EXPECT_EQ(summary["failed"].get<int>(), 1) << summary.dump(2);
  for (const char* name : {"textured-floor", "parallel-squares"}) {
    const fs::path glb = out / (std::string(name) + ".glb");
    ASSERT_TRUE(fs::exists(glb)) << name << "\n" << r;
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(glb.string(), 0);
    ASSERT_NE(scene, nullptr) << importer.GetErrorString();
    EXPECT_GT(scene->mNumMeshes, 0u);
    EXPECT_TRUE(scene->mMeshes[0]->HasVertexColors(0));
  }
  EXPECT_FALSE(fs::exists(out / "broken.glb"));
  EXPECT_FALSE(fs::exists(out / "broken"));
  // Nothing half-written beside them.
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace bounce::itest
