// The lit mesh as binary glTF, read back with Assimp (a second, independent
// glTF implementation): the same vertices, triangles and colours, the colours
// being the light times the exposure that maps the brightest luminance
// (the 99th percentile of four values is the largest) to 0.9.
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <assimp/Importer.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <vector>

#include "base/error.h"
#include "io/glb_writer.h"
#include "scratch_dir.h"

namespace bounce {
namespace {

struct Quad {
  std::vector<glm::vec3> positions{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  std::vector<glm::vec3> normals{{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  std::vector<glm::vec3> radiance{
      {0.1f, 0.2f, 0.3f}, {1.0f, 0.5f, 0.25f}, {4.0f, 4.0f, 4.0f}, {0, 0, 0}};
  std::vector<glm::uvec3> triangles{{0, 1, 2}, {0, 2, 3}};
};

float luminance_of(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

TEST(GlbWriter, AssimpReadsBackVerticesTrianglesAndColours) {
  const test::ScratchDir dir("bounce-glb");
  const Quad q;
  const float exposure =
      write_lit_glb(dir / "lit.glb", {q.positions, q.normals, q.radiance, q.triangles});
  const float expected_exposure = 0.9f / luminance_of(q.radiance[2]);
  EXPECT_NEAR(exposure, expected_exposure, 1e-6f * expected_exposure);

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile((dir / "lit.glb").string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const aiMesh* m = scene->mMeshes[0];
  ASSERT_EQ(m->mNumVertices, q.positions.size());
  ASSERT_TRUE(m->HasVertexColors(0));
  ASSERT_TRUE(m->HasNormals());
  for (unsigned v = 0; v < m->mNumVertices; ++v) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_FLOAT_EQ(m->mVertices[v][static_cast<unsigned>(c)], q.positions[v][c]);
      EXPECT_FLOAT_EQ(m->mNormals[v][static_cast<unsigned>(c)], q.normals[v][c]);
    }
    const aiColor4D got = m->mColors[0][v];
    const glm::vec3 want = glm::min(q.radiance[v] * expected_exposure, glm::vec3(1.0f));
    EXPECT_NEAR(got.r, want.r, 1e-5f) << "vertex " << v;
    EXPECT_NEAR(got.g, want.g, 1e-5f) << "vertex " << v;
    EXPECT_NEAR(got.b, want.b, 1e-5f) << "vertex " << v;
  }
  ASSERT_EQ(m->mNumFaces, q.triangles.size());
  for (unsigned f = 0; f < m->mNumFaces; ++f) {
    ASSERT_EQ(m->mFaces[f].mNumIndices, 3u);
    for (unsigned c = 0; c < 3; ++c)
      EXPECT_EQ(m->mFaces[f].mIndices[c], q.triangles[f][static_cast<int>(c)]);
  }
}

TEST(GlbWriter, ContainerLengthMatchesTheFile) {
  const test::ScratchDir dir("bounce-glb");
  const Quad q;
  write_lit_glb(dir / "lit.glb", {q.positions, q.normals, q.radiance, q.triangles});
  std::ifstream in(dir / "lit.glb", std::ios::binary);
  unsigned char h[12];
  in.read(reinterpret_cast<char*>(h), 12);
  ASSERT_TRUE(in);
  EXPECT_EQ(std::string(reinterpret_cast<char*>(h), 4), "glTF");
  const std::uint32_t version =
      h[4] | (h[5] << 8) | (h[6] << 16) | (static_cast<std::uint32_t>(h[7]) << 24);
  const std::uint32_t length =
      h[8] | (h[9] << 8) | (h[10] << 16) | (static_cast<std::uint32_t>(h[11]) << 24);
  EXPECT_EQ(version, 2u);
  EXPECT_EQ(length, std::filesystem::file_size(dir / "lit.glb"));
  EXPECT_EQ(length % 4, 0u);
}

TEST(GlbWriter, RefusesNaNAndEmptyMeshesWithoutWritingAFile) {
  const test::ScratchDir dir("bounce-glb");
  Quad q;
  q.radiance[1].g = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(write_lit_glb(dir / "nan.glb", {q.positions, q.normals, q.radiance, q.triangles}),
               Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "nan.glb"));
  const std::vector<glm::vec3> none;
  const std::vector<glm::uvec3> no_triangles;
  EXPECT_THROW(write_lit_glb(dir / "empty.glb", {none, none, none, no_triangles}), Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "empty.glb"));
  Quad bad;
  bad.triangles[1].z = 7;
  EXPECT_THROW(
      write_lit_glb(dir / "range.glb", {bad.positions, bad.normals, bad.radiance, bad.triangles}),
      Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "range.glb"));
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace bounce
