// `bounce solve` also writes the lit mesh as binary glTF (lit.glb). Read back
// with Assimp, a glTF reader independent of the writer, it must hold the PLY's
// mesh and light: the same vertices and triangles, and vertex colours that
// are the PLY's exact linear light times the exposure its header states,
// clamped to [0, 1].
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <regex>

#include "cli_harness.h"
#include "ply_vertices.h"
#include "solve_fixture.h"

namespace bounce::itest {
namespace {

TEST_F(Solve, GltfExportCarriesThePlyLight) {
  solve("glb", {"--no-images"});
  const fs::path out = tmp->path() / "glb";
  ASSERT_TRUE(fs::exists(out / "lit.glb"));
  const PlyVertices ply = read_ply_vertices(out / "lit.ply");
  std::smatch m;
  const std::string header = read_text(out / "lit.ply").substr(0, 1024);
  ASSERT_TRUE(std::regex_search(header, m, std::regex("exposure ([0-9.eE+-]+)"))) << header;
  const double exposure = std::stod(m[1].str());
  ASSERT_GT(exposure, 0.0);

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile((out / "lit.glb").string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const aiMesh* mesh = scene->mMeshes[0];
  ASSERT_EQ(mesh->mNumVertices, ply.rows.size());
  ASSERT_TRUE(mesh->HasVertexColors(0));
  const std::size_t x = ply.column("x"), r = ply.column("radiance_r");
  std::size_t lit = 0;
  for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
    for (unsigned c = 0; c < 3; ++c)
      ASSERT_FLOAT_EQ(mesh->mVertices[v][c], ply.rows[v][x + c]) << "vertex " << v;
    const aiColor4D colour = mesh->mColors[0][v];
    const float got[3] = {colour.r, colour.g, colour.b};
    for (unsigned c = 0; c < 3; ++c) {
      const double want = std::clamp(ply.rows[v][r + c] * exposure, 0.0, 1.0);
      // The PLY header prints the exposure to 9 digits.
      ASSERT_NEAR(got[c], want, 1e-6 + 1e-6 * want) << "vertex " << v << " channel " << c;
    }
    if (colour.r + colour.g + colour.b > 0.0f) ++lit;
  }
  EXPECT_GT(lit, mesh->mNumVertices / 2) << "most of the Cornell box is lit";
}

}  // namespace
}  // namespace bounce::itest
