// Light probes baked, written, read back and lit (runtime/light_probes.h,
// runtime/light_probe_placement.h, folder/light_probe_files.h): on the
// Cornell box the probes' SH gives, for the six axis normals, the irradiance
// the independent path tracer finds at the same points; the placement keeps
// no probe inside the boxes; too many probes are refused before any is
// traced, naming the setting; a damaged probe file is one error naming it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "bake/bake.h"
#include "bake/bake_writer.h"
#include "base/error.h"
#include "folder/bake_format.h"
#include "folder/light_probe_files.h"
#include "io/npy.h"
#include "patches/surface_patch_lookup.h"
#include "reference/path_tracer.h"
#include "reference/probe_reference_error.h"
#include "reference/probe_wall_agreement.h"
#include "relight/lighting_session.h"
#include "runtime/light_probe_gather.h"
#include "scene/scene_loader.h"
#include "scratch_dir.h"

namespace bounce {
namespace {

const std::string kCornell = std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-box";

Scene cornell() {
  Diagnostics d;
  return SceneLoader(d).load(kCornell);
}

BakeSettings probe_settings(int voxel) {
  BakeSettings s;
  s.voxel_resolution = voxel;
  s.codec = CodecChoice::Dense;
  s.pictures = false;
  s.light_probes = ProbePlacementMode::On;
  return s;
}

// Bakes the Cornell box with probes into dir / "bake".
BakeResult bake_into(const std::filesystem::path& dir, const Scene& scene, const BakeSettings& s) {
  Diagnostics d;
  Progress progress;
  BakeResult r = Baker(scene, s, d).run(progress);
  write_bake(dir / "bake", scene, r, d);
  return r;
}

// The probes' irradiance (indirect: light reflected at least once, what the
// SH holds) against the path tracer's at about 100 probes, for the six axis
// normals (reference/probe_reference_error.h): relative RMSE over points and
// channels, and the level sum probe / sum ref. The reference's own noise is
// independent of the probes' error, so the squared difference expected from
// it alone adds to the probes' squared error: the allowance is
// sqrt(target^2 + noise^2). Measured: at 8 voxels (138 probes, all
// measured) 0.070 with a reference noise of 0.029, level 0.991; at the
// scene's 16 voxels (1123 probes, 103 measured) 0.058 with noise 0.025,
// level 0.994.
TEST(LightProbes, CornellProbeShMatchesThePathTracerAtTheAxisNormals) {
  test::ScratchDir dir("bounce-light-probes");
  const Scene scene = cornell();
  bake_into(dir.path(), scene, probe_settings(8));
  LightingSessionSettings indirect;  // the path tracer's indirect light has no emission
  indirect.probe_emission = false;
  LightingSession session(dir.path() / "bake", indirect);
  ASSERT_TRUE(session.light_probes().has_value());
  const LightProbes& probes = *session.light_probes();
  ASSERT_GT(probes.size(), 50u);
  session.light();
  std::vector<glm::vec3> sh;
  session.probe_sh(sh);
  ASSERT_EQ(sh.size(), probes.size() * kShCoefficients);

  ReferenceSettings rs;
  rs.samples = 16384;
  const ReferencePathTracer pt(session.tracer(), rs);
  const ProbeReferenceError e = probe_reference_error(pt, probes.position, sh, 140);
  std::printf(
      "Cornell box, %zu probes, %zu measured x 6 normals: relative RMSE %.4f (reference "
      "noise %.4f, noise-corrected %.4f), level %.4f\n",
      probes.size(), e.probes_measured, e.relative_rmse, e.reference_noise, e.noise_corrected_rmse,
      e.level);
  EXPECT_EQ(e.probes_measured, probes.size());
  EXPECT_LT(e.relative_rmse, std::sqrt(0.08 * 0.08 + e.reference_noise * e.reference_noise));
  // The level's noise is that of a mean over hundreds of points: negligible.
  EXPECT_NEAR(e.level, 1.0, 0.03);
}

// The white furnace (a closed cube, albedo 0.5 and emission 1 on every
// wall): every wall leaves 1 / (1 - 0.5) = 2, of which 1 is emitted and 1
// reflected, and a closed surface of uniform exitance M gives irradiance M
// for every normal at every point inside. So each probe's SH gives 2 for
// the six axis normals with the walls' emission, and 1 without. Every ray
// of a probe's gather meets a wall, and an irradiance that is the same in
// every direction is the SH's first term alone, fitted exactly: what is
// left is the float32 rounding of the transport and the sums (measured
// under 1e-5).
TEST(LightProbes, FurnaceProbesSeeTheWallsEmissionAndTheirReflectedLight) {
  test::ScratchDir dir("bounce-light-probes");
  Diagnostics d;
  const Scene scene = SceneLoader(d).load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/furnace");
  BakeSettings s = probe_settings(8);
  bake_into(dir.path(), scene, s);
  for (const bool emission : {true, false}) {
    LightingSessionSettings settings;
    settings.probe_emission = emission;
    LightingSession session(dir.path() / "bake", settings);
    ASSERT_TRUE(session.light_probes().has_value());
    ASSERT_GT(session.light_probes()->size(), 8u);
    session.light();
    std::vector<glm::vec3> sh;
    session.probe_sh(sh);
    const float expected = emission ? 2.0f : 1.0f;
    for (std::size_t p = 0; p < session.light_probes()->size(); ++p)
      for (const glm::vec3 n : {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0),
                                glm::vec3(0, -1, 0), glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)}) {
        const glm::vec3 e = sh_irradiance(&sh[p * kShCoefficients], n);
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(e[c], expected, 1e-3f * expected)
              << "probe " << p << " normal " << n.x << "," << n.y << "," << n.z
              << (emission ? " with" : " without") << " emission";
      }
  }
}

// A probe just off a lit-mesh vertex on a flat open wall against the vertex
// (reference/probe_wall_agreement.h): the irradiance the probe's SH gives
// for the wall's normal is what the vertex gathers, to within the SH L2
// limit, at most 5%. Both gathers trace 2048 rays per point here, so that
// their Monte Carlo noise (about 6% per point at the default 256) does not
// hide the comparison. Measured on 141 vertices: 0.039, level 0.977; of
// it, the SH fit against the probe's own gather in the wall's direction is
// 0.013, and that gather against the vertex 0.042.
TEST(LightProbes, ProbeOnAWallAgreesWithTheWall) {
  test::ScratchDir dir("bounce-light-probes");
  const Scene scene = cornell();
  BakeSettings s = probe_settings(8);
  s.light_probes = ProbePlacementMode::Off;
  s.final_gather_rays = 2048;
  const BakeResult r = bake_into(dir.path(), scene, s);
  LightingSession session(dir.path() / "bake");
  session.light();
  const float cell = session.description().grid.cell_size;
  const std::vector<std::uint32_t> spots =
      open_wall_vertices(session.tracer(), session.mesh(), cell, 150);
  ASSERT_GT(spots.size(), 50u);
  const SurfacePatchLookup lookup(r.voxels, r.samples, r.patch_of_sample);
  const LightProbes probes =
      gather_light_probes(session.tracer(), lookup, r.patches.patches, r.voxels.grid,
                          probe_positions_off(session.mesh(), spots, 0.01f * cell), 2048, s.seed);
  std::vector<glm::vec3> irradiance, sh, wall;
  session.relighter().gather_far(probes.gather, irradiance);
  fit_probe_sh(irradiance, sh);
  session.vertex_irradiance(wall);
  const ProbeWallAgreement a = probe_wall_agreement(session.mesh(), wall, spots, sh);
  std::printf(
      "Cornell box, %zu vertices on flat open walls: probe against wall relative RMSE "
      "%.4f, level %.4f\n",
      a.spots, a.relative_rmse, a.level);
  EXPECT_LT(a.relative_rmse, 0.05);
  EXPECT_NEAR(a.level, 1.0, 0.03);
}

TEST(LightProbes, NoProbeStandsInsideTheBoxes) {
  test::ScratchDir dir("bounce-light-probes");
  const Scene scene = cornell();
  const BakeResult r = bake_into(dir.path(), scene, probe_settings(8));
  EXPECT_GT(r.probe_placement.rejected_enclosed, 0u);
  EXPECT_EQ(r.light_probes.size() + r.probe_placement.rejected_enclosed +
                r.probe_placement.rejected_sees_nothing,
            r.probe_placement.candidates);
  // Inside a closed box every axis ray meets the back of one of its faces.
  const RayTracer tracer(scene);
  for (const glm::vec3& p : r.light_probes.position) {
    int backs = 0;
    for (std::size_t k = 0; k < 6; ++k) {
      const glm::vec3 d = probe_directions()[k];
      const Hit h = tracer.intersect(p, d);
      if (h.hit && glm::dot(d, h.geometric_normal) > 0.0f && !scene.two_sided(h.triangle)) ++backs;
    }
    EXPECT_LT(backs, 6) << "probe at " << p.x << ", " << p.y << ", " << p.z;
  }
}

TEST(LightProbes, TooManyProbesAreRefusedNamingTheSetting) {
  const Scene scene = cornell();
  // The Cornell box at 8 voxels has 138 probes among more candidates.
  BakeSettings s = probe_settings(8);
  s.light_probes_max = 100;
  Diagnostics d;
  Progress progress;
  try {
    Baker(scene, s, d).run(progress);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("light_probes_max"), std::string::npos) << e.what();
  }
}

TEST(LightProbes, DamagedProbeFilesAreOneErrorNamingTheFile) {
  test::ScratchDir dir("bounce-light-probes");
  const Scene scene = cornell();
  const BakeResult r = bake_into(dir.path(), scene, probe_settings(4));
  const std::filesystem::path bake = dir.path() / "bake";
  const auto read = [&] {
    return read_light_probes(bake, r.patches.size(), r.samples.samples.size());
  };
  ASSERT_TRUE(read().has_value());
  EXPECT_EQ(read()->size(), r.light_probes.size());
  const auto expect_error_naming = [&](const std::string& file) {
    try {
      read();
      ADD_FAILURE() << "expected an error naming " << file;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
    }
  };
  // One probe fewer than the gather has rows for.
  std::vector<float> fewer(3 * (r.light_probes.size() - 1), 0.5f);
  write_npy(bake / bake_file::kProbePositions, fewer, {r.light_probes.size() - 1, 3});
  expect_error_naming("probe_gather_first.npy");
  // Positions of the wrong shape.
  write_npy(bake / bake_file::kProbePositions, fewer, {fewer.size()});
  expect_error_naming(bake_file::kProbePositions);
  // A non-finite position.
  std::vector<float> positions(3 * r.light_probes.size(), 0.5f);
  positions[4] = std::nanf("");
  write_npy(bake / bake_file::kProbePositions, positions, {r.light_probes.size(), 3});
  expect_error_naming(bake_file::kProbePositions);
}

}  // namespace
}  // namespace bounce
