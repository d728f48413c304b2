// A scene whose mesh file embeds its textures, through the CLI: the shipped
// textured-floor scene exported as binary glTF (`bounce bake --export-glb`,
// which embeds checker.png byte for byte and the fence's mask as a PNG's
// alpha) is the mesh of a second scene with the same sun and camera. Baking
// it reads the embedded images without a warning about them; its own
// export embeds the same bytes again; and `bounce solve`'s camera picture
// shows the checker: the direct light of neighbouring squares' centres
// differs by the ratio of the checker's two colours (decoded here from
// their sRGB bytes), the light itself being smooth across the floor.
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cli_harness.h"
#include "scene/texture.h"

namespace bounce::itest {
namespace {

double decode(int byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

const std::vector<std::string> kSmall = {
    "--voxel", "4",     "--closure-rays", "64",     "--final-gather-rays", "32",
    "--codec", "dense", "--no-pictures",  "--quiet"};

// `bounce bake SCENE --export-glb` into OUT; the glb is OUT.glb.
RunResult bake_and_export(const fs::path& scene, const fs::path& out, const fs::path& cwd) {
  std::vector<std::string> args = {"bake", scene.string(), "--export-glb", "--out", out.string()};
  args.insert(args.end(), kSmall.begin(), kSmall.end());
  return run(args, cwd);
}

// The bytes of the base colour image each material of a .glb embeds.
std::map<std::string, std::string> embedded_images(const fs::path& glb) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(glb.string(), 0);
  EXPECT_NE(scene, nullptr) << importer.GetErrorString();
  std::map<std::string, std::string> images;
  if (scene == nullptr) return images;
  for (unsigned m = 0; m < scene->mNumMaterials; ++m) {
    aiString path;
    if (scene->mMaterials[m]->GetTexture(aiTextureType_DIFFUSE, 0, &path) != aiReturn_SUCCESS)
      continue;
    const aiTexture* texture = scene->GetEmbeddedTexture(path.C_Str());
    EXPECT_NE(texture, nullptr) << path.C_Str();
    if (texture == nullptr || texture->mHeight != 0) continue;
    images[scene->mMaterials[m]->GetName().C_Str()] =
        std::string(reinterpret_cast<const char*>(texture->pcData), texture->mWidth);
  }
  return images;
}

TEST(EmbeddedTextures, GlbSceneBakesExportsAndSolvesWithItsEmbeddedTextures) {
  TempDir tmp;
  const RunResult first = bake_and_export(kScenes / "textured-floor", tmp / "floor", tmp.path());
  ASSERT_EQ(first.exit_code, 0) << first;
  const fs::path scene_dir = tmp / "glb-scene";
  fs::create_directories(scene_dir);
  // textured-floor's sun and camera: straight above, the floor filling the
  // picture's height.
  write_text(scene_dir / "scene.json", R"({
    "meshes": [ { "file": "../floor.glb" } ],
    "lights": [ { "name": "sun", "type": "directional", "direction": [0, -1, 0], "intensity": 1 } ],
    "camera": { "position": [0, 3, 0], "target": [0, 0, 0], "up": [0, 0, -1],
                "fov_y_deg": 36.869898 } })");

  const RunResult again = bake_and_export(scene_dir, tmp / "again", tmp.path());
  ASSERT_EQ(again.exit_code, 0) << again;
  for (const std::string& w : lines_starting_with(again.err, "bounce: warning"))
    for (const char* word : {"embedded", "cannot read", "not found", "texture '", "mask ("})
      EXPECT_FALSE(contains(w, word)) << w;

  // The export of the embedded textures copies their bytes.
  const std::map<std::string, std::string> before = embedded_images(tmp / "floor.glb");
  const std::map<std::string, std::string> after = embedded_images(tmp / "again.glb");
  ASSERT_EQ(before.count("floor"), 1u);
  EXPECT_EQ(before.at("floor"), read_text(kScenes / "textured-floor" / "checker.png"));
  EXPECT_EQ(after, before);

  const RunResult solved =
      run({"solve", (tmp / "again").string(), "--quiet", "--out", (tmp / "solved").string()},
          tmp.path());
  ASSERT_EQ(solved.exit_code, 0) << solved;
  std::string error;
  const std::optional<ImagePixels> direct =
      read_image_pixels(tmp / "solved" / "camera_direct.exr", error);
  ASSERT_TRUE(direct.has_value()) << error;
  ASSERT_EQ(direct->channels, 3);
  // The floor is 2 m across and fills the picture's height: a square is an
  // eighth of it, centred horizontally.
  const int square = direct->height / 8, left = (direct->width - direct->height) / 2;
  const auto centre = [&](int i, int j) {
    const auto p = static_cast<std::size_t>((j * square + square / 2) * direct->width + left +
                                            i * square + square / 2);
    return glm::dvec3(direct->pixels[3 * p], direct->pixels[3 * p + 1], direct->pixels[3 * p + 2]);
  };
  const glm::dvec3 a(decode(224), decode(96), decode(64)), b(decode(48), decode(128), decode(192));
  const bool first_is_a = centre(1, 1).x > centre(1, 1).y;  // a is reddish, b bluish
  for (int j = 1; j < 7; ++j)
    for (int i = 1; i < 6; ++i) {
      const glm::dvec3 here = centre(i, j), right = centre(i + 1, j);
      ASSERT_GT(glm::min(here.x, glm::min(here.y, here.z)), 0.0) << i << "," << j;
      // One is colour a, the other b; which, alternates.
      const glm::dvec3 ratio = here / right;
      const bool here_is_a = ((i + j) % 2 == 0) == first_is_a;
      const glm::dvec3 want = here_is_a ? a / b : b / a;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(ratio[c] / want[c], 1.0, 0.03)
            << "squares " << i << "," << j << " channel " << c;
    }
}

}  // namespace
}  // namespace bounce::itest
