// Light probes' SH between the probes (runtime/probe_interpolation.h): a
// closed room split by a wall thinner than a voxel, a lamp on one side.
// Next to the wall on the dark side the blend of the probes that see the
// point carries none of the lit side's light: it is as far from the path
// tracer as its dark-side probes are at their own positions, while the same
// weights without the visibility test carry the lit side's light through:
// the test is what stops the leak. On the lit side the blend matches the path
// tracer. At a probe's own position the blend is that probe's SH exactly,
// and everywhere the weights sum to 1.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <random>
#include <string>

#include "bake/bake.h"
#include "bake/bake_writer.h"
#include "reference/path_tracer.h"
#include "relight/lighting_session.h"
#include "scene/scene_loader.h"
#include "scratch_dir.h"

namespace bounce {
namespace {

// The room spans [0, 2] x [0, 1] x [0, 1]; the wall is the pair of faces
// x = kWallDark (facing the dark side, -x) and x = kWallLit (facing +x). At
// 8 voxels the grid's cells are 0.2500625 wide from x = -0.00025: the wall
// lies in the lit half of cell 4 (0.99999 to 1.25006, centre 1.125), so a
// point just on its dark side, beyond that centre, has the wall's cell
// and the lit side's cell 5 as its trilinear neighbours along x.
constexpr float kWallDark = 1.15f;
constexpr float kWallLit = 1.17f;

// A quad's OBJ faces (two triangles) wound so that its normal is `facing`.
std::string quad(int& next, const glm::vec3 (&v)[4], const glm::vec3& facing) {
  std::string s;
  for (const glm::vec3& p : v)
    s += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
  const bool along = glm::dot(glm::cross(v[1] - v[0], v[2] - v[0]), facing) > 0.0f;
  const int a = next, b = next + 1, c = next + 2, d = next + 3;
  next += 4;
  const auto tri = [](int x, int y, int z) {
    return "f " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
  };
  return s + (along ? tri(a, b, c) + tri(a, c, d) : tri(a, c, b) + tri(a, d, c));
}

std::filesystem::path write_thin_wall_scene(const std::filesystem::path& dir) {
  int next = 1;
  std::string obj = "mtllib room.mtl\nusemtl grey\n";
  const auto x_face = [&](float x, float facing) {
    obj += quad(next, {{x, 0, 0}, {x, 1, 0}, {x, 1, 1}, {x, 0, 1}}, {facing, 0, 0});
  };
  x_face(0.0f, 1.0f);
  x_face(2.0f, -1.0f);
  x_face(kWallDark, -1.0f);
  x_face(kWallLit, 1.0f);
  for (const float y : {0.0f, 1.0f})
    obj += quad(next, {{0, y, 0}, {2, y, 0}, {2, y, 1}, {0, y, 1}}, {0, y == 0.0f ? 1 : -1, 0});
  for (const float z : {0.0f, 1.0f})
    obj += quad(next, {{0, 0, z}, {2, 0, z}, {2, 1, z}, {0, 1, z}}, {0, 0, z == 0.0f ? 1 : -1});
  std::ofstream(dir / "room.mtl") << "newmtl grey\nKd 0.7 0.7 0.7\n";
  std::ofstream(dir / "room.obj") << obj;
  std::ofstream(dir / "scene.json") << R"({"meshes": [{"file": "room.obj"}],
    "lights": [{"name": "lamp", "type": "point", "position": [1.7, 0.8, 0.5],
                "color": [1, 1, 1], "intensity": 1.0}]})";
  return dir / "scene.json";
}

// One bake for every test: the room at 8 voxels with probes, lit once.
class ProbeInterpolationThinWall : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<test::ScratchDir>("bounce-probe-interp");
    // Dense: the transport exactly as solved, so that what the probes hold
    // is the bake's light and not compression's.
    BakeSettings s;
    s.light_probes = ProbePlacementMode::On;
    s.voxel_resolution = 8;
    s.codec = CodecChoice::Dense;
    s.pictures = false;
    Diagnostics d;
    Progress progress;
    const Scene scene = SceneLoader(d).load(write_thin_wall_scene(dir_->path()));
    const BakeResult result = Baker(scene, s, d).run(progress);
    straddling_ = patches_on_both_sides(result);
    separated_pairs_ = result.clustering.separated_sample_pairs;
    write_bake(dir_->path() / "bake", scene, result, d);
    session_ = std::make_unique<LightingSession>(dir_->path() / "bake");
    session_->light();
  }
  static void TearDownTestSuite() {
    session_.reset();
    dir_.reset();
  }
  // Patches with samples beyond the wall on both sides (x < kWallDark and
  // x > kWallLit): each would carry the lit side's light to the dark side.
  static std::size_t patches_on_both_sides(const BakeResult& r) {
    std::size_t count = 0;
    for (std::size_t p = 0; p < r.patches.size(); ++p) {
      bool dark = false, lit = false;
      for (std::uint32_t k = r.patches.member_first[p]; k < r.patches.member_first[p + 1]; ++k) {
        const float x = r.samples.samples[r.patches.member_samples[k]].position.x;
        dark = dark || x < kWallDark;
        lit = lit || x > kWallLit;
      }
      if (dark && lit) ++count;
    }
    return count;
  }
  static std::unique_ptr<test::ScratchDir> dir_;
  static std::unique_ptr<LightingSession> session_;
  static std::size_t straddling_, separated_pairs_;
};
std::size_t ProbeInterpolationThinWall::straddling_ = 0;
std::size_t ProbeInterpolationThinWall::separated_pairs_ = 0;
std::unique_ptr<test::ScratchDir> ProbeInterpolationThinWall::dir_;
std::unique_ptr<LightingSession> ProbeInterpolationThinWall::session_;

struct AxisIrradiance {
  glm::vec3 value[6];
};

AxisIrradiance axes_of(const std::array<glm::vec3, kShCoefficients>& sh) {
  AxisIrradiance a;
  for (std::size_t k = 0; k < 6; ++k) a.value[k] = sh_irradiance(sh.data(), probe_directions()[k]);
  return a;
}

// The path tracer's indirect irradiance at `point` for the six axis
// normals, with the variance of each mean.
PointReference reference_at(const RayTracer& tracer, const glm::vec3& point) {
  ReferenceSettings rs;
  rs.samples = 32768;
  std::vector<ReferencePoint> points;
  for (std::size_t k = 0; k < 6; ++k)
    points.push_back({point, probe_directions()[k], glm::vec3(0.0f), glm::vec3(0.0f)});
  return ReferencePathTracer(tracer, rs).estimate_points(points);
}

// The floor, ceiling and side walls in the wall's voxel column lie on both
// sides of it; the clustering keeps each side's samples in patches of their
// own, so no patch averages the two sides' light.
TEST_F(ProbeInterpolationThinWall, NoPatchHoldsSurfaceOnBothSidesOfTheWall) {
  EXPECT_GT(separated_pairs_, 0u);
  EXPECT_EQ(straddling_, 0u);
}

TEST_F(ProbeInterpolationThinWall, DarkSideNextToTheWallGetsNoLightFromTheLitSide) {
  LightingSession& session = *session_;
  const glm::vec3 dark(1.14f, 0.45f, 0.55f), lit(1.18f, 0.45f, 0.55f);
  const std::vector<glm::vec3>& positions = session.light_probes()->position;

  std::array<glm::vec3, kShCoefficients> sh_dark, sh_naive, sh_lit;
  const ProbeBlend tested = session.probe_sh_at(dark, sh_dark);
  const ProbeBlend naive = session.probe_sh_at(dark, sh_naive, ProbeVisibility::kIgnored);
  session.probe_sh_at(lit, sh_lit);
  // The geometry the test is about: without the visibility test the dark
  // point's neighbours are the lit side's probes; with it, the dark side's.
  ASSERT_GT(naive.count, 0u);
  for (std::size_t i = 0; i < naive.count; ++i) EXPECT_GT(positions[naive.probe[i]].x, kWallLit);
  ASSERT_GT(tested.count, 0u);
  for (std::size_t i = 0; i < tested.count; ++i) EXPECT_LT(positions[tested.probe[i]].x, kWallDark);

  const PointReference ref_dark = reference_at(session.tracer(), dark);
  const PointReference ref_lit = reference_at(session.tracer(), lit);
  const AxisIrradiance e_dark = axes_of(sh_dark), e_naive = axes_of(sh_naive),
                       e_lit = axes_of(sh_lit);
  // The scale: the lit side's mean indirect irradiance next to the wall.
  double level = 0.0, diff_sq = 0.0, ref_sq = 0.0, var = 0.0;
  for (std::size_t k = 0; k < 6; ++k)
    for (int c = 0; c < 3; ++c) {
      const double r = ref_lit.indirect_irradiance[k][c];
      level += r / 18.0;
      diff_sq += (e_lit.value[k][c] - r) * (e_lit.value[k][c] - r);
      ref_sq += r * r;
      var += ref_lit.indirect_variance[k][c];
    }
  ASSERT_GT(level, 0.0);
  const double lit_rmse = std::sqrt(diff_sq / ref_sq), lit_noise = std::sqrt(var / ref_sq);
  // The dark side's probes are not quite dark (1.3% of the lit level, the
  // error of the patches' light next to the wall); that error is the
  // probes' own, measured at the blended probes against the path tracer
  // there, and the blend must add nothing to it.
  const std::vector<glm::vec3> all_sh = [&] {
    std::vector<glm::vec3> sh;
    session.probe_sh(sh);
    return sh;
  }();
  double probes_own = 0.0;
  for (std::size_t i = 0; i < tested.count; ++i) {
    const std::uint32_t p = tested.probe[i];
    const PointReference ref = reference_at(session.tracer(), positions[p]);
    for (std::size_t k = 0; k < 6; ++k) {
      const glm::vec3 e = sh_irradiance(all_sh.data() + p * kShCoefficients, probe_directions()[k]);
      for (int c = 0; c < 3; ++c)
        probes_own = std::max(probes_own, std::abs(e[c] - ref.indirect_irradiance[k][c]) +
                                              3.0 * std::sqrt(ref.indirect_variance[k][c]));
    }
  }
  double dark_max = 0.0, naive_min = 1e30, ref_dark_max = 0.0;
  for (std::size_t k = 0; k < 6; ++k)
    for (int c = 0; c < 3; ++c) {
      const double r = ref_dark.indirect_irradiance[k][c];
      const double sigma3 = 3.0 * std::sqrt(ref_dark.indirect_variance[k][c]);
      ref_dark_max = std::max(ref_dark_max, r + sigma3);
      dark_max = std::max(dark_max, std::abs(e_dark.value[k][c] - r) - sigma3);
      naive_min = std::min(naive_min, std::abs(e_naive.value[k][c] - r) - sigma3);
    }
  std::printf(
      "thin wall: lit-side level %.4g; lit point relative RMSE %.4f (reference noise %.4f); "
      "dark point: reference up to %.3g, blend off by up to %.3g (the blended probes' own "
      "error %.3g, %.1f%% of the lit level), naive blend off by at least %.3g (%.1f%%); "
      "rays %d, stage %d\n",
      level, lit_rmse, lit_noise, ref_dark_max, dark_max, probes_own, 100.0 * probes_own / level,
      naive_min, 100.0 * naive_min / level, tested.rays, static_cast<int>(tested.stage));
  // No path reaches the dark side: the reference there is zero to its noise.
  EXPECT_LT(ref_dark_max, 1e-3 * level);
  // No patch holds surface on both sides of the wall, so the probes there
  // carry at most a trace of the lit side's light (7.6% of its level when
  // the floor's patches spanned both sides).
  EXPECT_LT(probes_own, 0.025 * level);
  EXPECT_LT(dark_max, 0.025 * level);
  // The blend at the point is off by no more than its probes are at their
  // own positions, give or take 1% of the lit level for how the dark
  // side's leaked light changes over a voxel.
  EXPECT_LE(dark_max, probes_own + 0.01 * level);
  // Without the visibility test the lit side's light is there, in every
  // direction and channel, several times the probes' own error.
  EXPECT_GT(naive_min, 0.2 * level);
  EXPECT_GT(naive_min, 4.0 * probes_own);
  // On the lit side the blend of probes a voxel or so away matches the
  // path tracer at the point: the SH's own error (about 0.07 at probes,
  // tests/unit/test_light_probes.cpp) plus the change of the light over
  // that distance, with the reference's noise added in quadrature.
  EXPECT_LT(lit_rmse, std::sqrt(0.2 * 0.2 + lit_noise * lit_noise));
}

TEST_F(ProbeInterpolationThinWall, AtAProbeTheBlendIsThatProbeExactly) {
  LightingSession& session = *session_;
  const std::vector<glm::vec3>& positions = session.light_probes()->position;
  std::vector<glm::vec3> all;
  session.probe_sh(all);
  ASSERT_GT(positions.size(), 10u);
  for (std::size_t p = 0; p < positions.size(); ++p) {
    std::array<glm::vec3, kShCoefficients> sh;
    const ProbeBlend b = session.probe_sh_at(positions[p], sh);
    ASSERT_EQ(b.count, 1u) << "probe " << p;
    EXPECT_EQ(b.probe[0], p);
    EXPECT_EQ(b.weight[0], 1.0f);
    for (std::size_t j = 0; j < kShCoefficients; ++j)
      EXPECT_EQ(sh[j], all[p * kShCoefficients + j]) << "probe " << p << " coefficient " << j;
  }
}

TEST_F(ProbeInterpolationThinWall, WeightsSumToOneAndStayOnThePointsSide) {
  LightingSession& session = *session_;
  const std::vector<glm::vec3>& positions = session.light_probes()->position;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> x(0.02f, 1.98f), yz(0.02f, 0.98f);
  int blends = 0, stages[4] = {0, 0, 0, 0}, rays = 0;
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 point(x(rng), yz(rng), yz(rng));
    if (point.x > kWallDark - 1e-3f && point.x < kWallLit + 1e-3f) continue;  // in the wall
    std::array<glm::vec3, kShCoefficients> sh;
    const ProbeBlend b = session.probe_sh_at(point, sh);
    ASSERT_GT(b.count, 0u) << point.x << ", " << point.y << ", " << point.z;
    float total = 0.0f;
    for (std::size_t k = 0; k < b.count; ++k) {
      EXPECT_GE(b.weight[k], 0.0f);
      total += b.weight[k];
      // No probe across the wall ever takes part.
      EXPECT_EQ(positions[b.probe[k]].x < kWallDark, point.x < kWallDark)
          << point.x << ", " << point.y << ", " << point.z;
    }
    EXPECT_NEAR(total, 1.0f, 1e-5f);
    ++blends;
    ++stages[static_cast<int>(b.stage)];
    rays += b.rays;
  }
  std::printf(
      "%d blends: %d trilinear, %d from the 27 cells, %d from the nearest probe; %.1f rays "
      "each\n",
      blends, stages[0], stages[1], stages[2], static_cast<double>(rays) / blends);
}

}  // namespace
}  // namespace bounce
