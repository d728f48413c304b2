// Samples of one surface with something standing between them are kept
// apart (patches/sample_separation.h); a curved surface's own samples are
// not. Two scenes in one voxel each: a floor with a thin wall standing on it
// (both faces in the voxel), and a closed sphere, whose samples face every
// way, so the voxel is tested, but between none of which anything stands.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "base/diagnostics.h"
#include "patches/sample_separation.h"
#include "patches/samples.h"
#include "raytrace/ray_tracer.h"
#include "scene/scene_loader.h"
#include "scratch_dir.h"
#include "voxel/voxelization.h"

namespace bounce {
namespace {

struct OneVoxel {
  Scene scene;
  std::unique_ptr<RayTracer> tracer;
  Voxelization voxels;
  SampleSet samples;
};

OneVoxel load_in_one_voxel(const test::ScratchDir& dir, const std::string& obj) {
  std::ofstream(dir.path() / "m.mtl") << "newmtl grey\nKd 0.5 0.5 0.5\n";
  std::ofstream(dir.path() / "m.obj") << "mtllib m.mtl\nusemtl grey\n" << obj;
  std::ofstream(dir.path() / "scene.json") << R"({"meshes": [{"file": "m.obj"}]})";
  Diagnostics d;
  OneVoxel v{SceneLoader(d).load(dir.path() / "scene.json"), nullptr, {}, {}};
  v.tracer = std::make_unique<RayTracer>(v.scene);
  v.voxels = voxelize(v.scene, VoxelGrid(v.scene.bounds(), 1));
  SamplingSettings sampling;
  sampling.samples_per_face = 8;
  v.samples = generate_samples(v.scene, *v.tracer, v.voxels, sampling);
  return v;
}

// A floor [0,1] x [0,1] at y = 0 facing up, and a wall 2 cm thick across it
// at x = 0.5, 0.6 high: its faces at x = 0.49 (facing -x) and 0.51 (+x).
std::string floor_and_wall() {
  return "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\n"
         "v 0.49 0 0\nv 0.49 0.6 0\nv 0.49 0.6 1\nv 0.49 0 1\n"
         "v 0.51 0 0\nv 0.51 0.6 0\nv 0.51 0.6 1\nv 0.51 0 1\n"
         "f 1 3 2\nf 1 4 3\n"
         "f 5 7 6\nf 5 8 7\n"
         "f 9 10 11\nf 9 11 12\n";
}

// A UV sphere of radius 0.4 about the origin, faces wound outwards.
std::string sphere() {
  constexpr int kRings = 16, kSegments = 32;
  const double pi = std::acos(-1.0);
  std::string obj;
  for (int r = 0; r <= kRings; ++r)
    for (int s = 0; s < kSegments; ++s) {
      const double theta = pi * r / kRings, phi = 2.0 * pi * s / kSegments;
      obj += "v " + std::to_string(0.4 * std::sin(theta) * std::cos(phi)) + " " +
             std::to_string(0.4 * std::cos(theta)) + " " +
             std::to_string(0.4 * std::sin(theta) * std::sin(phi)) + "\n";
    }
  const auto at = [&](int r, int s) { return std::to_string(r * kSegments + s % kSegments + 1); };
  for (int r = 0; r < kRings; ++r)
    for (int s = 0; s < kSegments; ++s) {
      if (r > 0) obj += "f " + at(r, s) + " " + at(r, s + 1) + " " + at(r + 1, s) + "\n";
      if (r + 1 < kRings)
        obj += "f " + at(r, s + 1) + " " + at(r + 1, s + 1) + " " + at(r + 1, s) + "\n";
    }
  return obj;
}

TEST(SampleSeparation, FloorOnTheTwoSidesOfAThinWallIsSeparatedAndOneSideIsNot) {
  const test::ScratchDir dir("bounce-separation");
  const OneVoxel v = load_in_one_voxel(dir, floor_and_wall());
  ASSERT_EQ(v.voxels.voxels.size(), 1u);
  const SampleSeparation separation(*v.tracer, v.samples, 0);
  ASSERT_FALSE(separation.empty());
  std::size_t across = 0, beside = 0;
  for (std::size_t a = 0; a < v.samples.samples.size(); ++a)
    for (std::size_t b = a + 1; b < v.samples.samples.size(); ++b) {
      const Sample& x = v.samples.samples[a];
      const Sample& y = v.samples.samples[b];
      if (x.normal.y < 0.99f || y.normal.y < 0.99f) continue;  // floor pairs only
      // Floor under the wall, between its faces, is on neither side.
      if (std::abs(x.position.x - 0.5f) < 0.02f || std::abs(y.position.x - 0.5f) < 0.02f) continue;
      const bool apart = (separation.row(a)[b / 64] >> (b % 64)) & 1u;
      if ((x.position.x < 0.49f) != (y.position.x < 0.49f)) {
        EXPECT_TRUE(apart) << "floor samples at x = " << x.position.x << " and " << y.position.x;
        ++across;
      } else {
        EXPECT_FALSE(apart) << "floor samples at x = " << x.position.x << " and " << y.position.x;
        ++beside;
      }
    }
  EXPECT_GT(across, 0u);
  EXPECT_GT(beside, 0u);
  EXPECT_GE(separation.separated_pairs(), across);
}

TEST(SampleSeparation, ASpheresOwnSamplesAreNeverSeparated) {
  const test::ScratchDir dir("bounce-separation");
  const OneVoxel v = load_in_one_voxel(dir, sphere());
  ASSERT_EQ(v.voxels.voxels.size(), 1u);
  ASSERT_GT(v.samples.samples.size(), 100u);
  const SampleSeparation separation(*v.tracer, v.samples, 0);
  EXPECT_GT(separation.rays(), 0u) << "samples face opposite ways: the voxel must be tested";
  EXPECT_EQ(separation.separated_pairs(), 0u);
}

}  // namespace
}  // namespace bounce
