// Probe volumes (runtime/probe_volume.h): boxes of light probes at a
// spacing of their own. Their text round-trips and bad text is one error
// naming the setting; a volume's lattice is centred in its box; on the
// Cornell box a volume's probes stand on its lattice, are written and read
// back with it, and a point inside the volume blends exactly the trilinear
// weights of its lattice's probes; their SH is as close to the path tracer
// as the probes next to the surfaces; a volume outside the scene, one too
// dense for the limit, and a damaged probe_volume.npy are refused before
// anything is traced, naming the setting or the file; with placement auto
// a grid with too many candidates keeps its volumes and says why it placed
// none next to the surfaces.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <string>

#include "bake/bake.h"
#include "bake/bake_writer.h"
#include "base/error.h"
#include "folder/bake_format.h"
#include "folder/light_probe_files.h"
#include "io/npy.h"
#include "reference/path_tracer.h"
#include "reference/probe_reference_error.h"
#include "relight/lighting_session.h"
#include "runtime/probe_volume.h"
#include "scene/scene_loader.h"
#include "scratch_dir.h"

namespace bounce {
namespace {

const std::string kCornell = std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-box";
// Inside the Cornell box (x and z from -1 to 1, y from 0 to 2), above the
// two boxes' tops (0.6 and 1.2): 5 x 3 x 5 probes 0.25 apart, every
// coordinate exact in binary.
const char* kVolume = "-0.5,1.25,-0.5,0.5,1.75,0.5,0.25";
constexpr std::size_t kVolumeProbes = 5 * 3 * 5;

Scene cornell() {
  Diagnostics d;
  return SceneLoader(d).load(kCornell);
}

BakeSettings volume_settings(ProbePlacementMode mode, const std::string& volumes) {
  BakeSettings s;
  s.voxel_resolution = 8;
  s.codec = CodecChoice::Dense;
  s.pictures = false;
  s.light_probes = mode;
  s.light_probe_volumes = volumes;
  return s;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

TEST(ProbeVolumeText, RoundTripsAndRefusesWhatIsNotAVolume) {
  const std::vector<ProbeVolume> v =
      parse_probe_volumes(" -1, 0,0.5, 1,2,3, 0.25 ;0,0,0,1,1,1,1e-1", "light_probe_volumes");
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0].lo, glm::vec3(-1.0f, 0.0f, 0.5f));
  EXPECT_EQ(v[0].hi, glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(v[0].spacing, 0.25f);
  EXPECT_EQ(v[1].spacing, 0.1f);
  const std::vector<ProbeVolume> again =
      parse_probe_volumes(probe_volumes_text(v), "light_probe_volumes");
  ASSERT_EQ(again.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(again[i].lo, v[i].lo);
    EXPECT_EQ(again[i].hi, v[i].hi);
    EXPECT_EQ(again[i].spacing, v[i].spacing);
  }
  EXPECT_TRUE(parse_probe_volumes("  ", "light_probe_volumes").empty());
  for (const char* bad :
       {"1,2,3", "0,0,0,1,1,1,0", "0,0,0,1,1,1,-0.5", "1,0,0,0,1,1,0.5", "0,0,0,1,1,1,nan",
        "0,0,0,1,1,1,inf", "0,0,0,1,1,1,x", "0,0,0,1,1,1,0.5;", "0,0,0,1,1,1,0.5,"}) {
    const std::string e = error_of([&] { parse_probe_volumes(bad, "light_probe_volumes"); });
    EXPECT_TRUE(contains(e, "light_probe_volumes")) << bad << ": " << e;
  }
}

TEST(ProbeVolumeLattice, IsCentredInTheBox) {
  // 1.0 / 0.3: 3 whole spacings, 4 probes, 0.1 of slack split on both sides.
  const ProbeVolume v{{0.0f, 0.0f, 0.0f}, {1.0f, 0.1f, 0.6f}, 0.3f};
  const TransferGrid g = volume_lattice(v);
  EXPECT_EQ(g.dims, glm::ivec3(4, 1, 3));
  EXPECT_EQ(volume_point_count(v), 12.0);
  const auto centre = [&](int a, int i) {
    return g.origin[a] + g.cell_size * (static_cast<float>(i) + 0.5f);
  };
  EXPECT_NEAR(centre(0, 0), 0.05f, 1e-6f);
  EXPECT_NEAR(centre(0, 3), 0.95f, 1e-6f);
  EXPECT_NEAR(centre(1, 0), 0.05f, 1e-6f);  // narrower than the spacing: its middle
  EXPECT_NEAR(centre(2, 0), 0.0f, 1e-6f);
  EXPECT_NEAR(centre(2, 2), 0.6f, 1e-6f);
  // An absurd spacing counts without overflow.
  EXPECT_GT(volume_point_count({{0, 0, 0}, {1e6f, 1e6f, 1e6f}, 1e-6f}), 1e35);
}

// One bake of the Cornell box with the volume, written and opened.
class CornellVolume : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<test::ScratchDir>("bounce-probe-volumes");
    scene_ = std::make_unique<Scene>(cornell());
    Diagnostics d;
    Progress progress;
    result_ = std::make_unique<BakeResult>(
        Baker(*scene_, volume_settings(ProbePlacementMode::On, kVolume), d).run(progress));
    write_bake(dir_->path() / "bake", *scene_, *result_, d);
    LightingSessionSettings indirect;  // what the path tracer's indirect light holds
    indirect.probe_emission = false;
    session_ = std::make_unique<LightingSession>(dir_->path() / "bake", indirect);
    session_->light();
  }
  static void TearDownTestSuite() {
    session_.reset();
    result_.reset();
    scene_.reset();
    dir_.reset();
  }
  static std::unique_ptr<test::ScratchDir> dir_;
  static std::unique_ptr<Scene> scene_;
  static std::unique_ptr<BakeResult> result_;
  static std::unique_ptr<LightingSession> session_;
};
std::unique_ptr<test::ScratchDir> CornellVolume::dir_;
std::unique_ptr<Scene> CornellVolume::scene_;
std::unique_ptr<BakeResult> CornellVolume::result_;
std::unique_ptr<LightingSession> CornellVolume::session_;

TEST_F(CornellVolume, ItsProbesStandOnItsLatticeAfterTheSurfaces) {
  const BakeResult& r = *result_;
  ASSERT_EQ(r.probe_placement.volumes.size(), 1u);
  const VolumePlacement& vp = r.probe_placement.volumes[0];
  EXPECT_EQ(vp.candidates, kVolumeProbes);
  EXPECT_EQ(vp.placed + vp.rejected_enclosed + vp.rejected_sees_nothing, vp.candidates);
  // Open air above the boxes: nothing there is enclosed.
  EXPECT_EQ(vp.placed, vp.candidates);
  ASSERT_EQ(r.light_probes.volumes.size(), 1u);
  const ProbeLattice& lattice = r.light_probes.volumes[0];
  EXPECT_EQ(lattice.count, vp.placed);
  EXPECT_EQ(lattice.first + lattice.count, r.light_probes.size());
  EXPECT_TRUE(r.probe_placement.surfaces);
  EXPECT_GT(lattice.first, 0u);  // the probes next to the surfaces come first
  for (std::size_t p = lattice.first; p < r.light_probes.size(); ++p) {
    const glm::vec3 at = r.light_probes.position[p];
    const glm::vec3 steps = (at - glm::vec3(-0.5f, 1.25f, -0.5f)) / 0.25f;
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(steps[a], std::round(steps[a]), 1e-4f) << p;
  }
  // Read back with its lattice.
  const std::optional<LightProbes>& read = session_->light_probes();
  ASSERT_TRUE(read.has_value());
  ASSERT_EQ(read->volumes.size(), 1u);
  EXPECT_EQ(read->volumes[0].first, lattice.first);
  EXPECT_EQ(read->volumes[0].count, lattice.count);
  EXPECT_EQ(read->volumes[0].grid.dims, lattice.grid.dims);
  EXPECT_EQ(read->volumes[0].grid.origin, lattice.grid.origin);
  EXPECT_EQ(read->volumes[0].grid.cell_size, lattice.grid.cell_size);
}

TEST_F(CornellVolume, APointInsideBlendsItsLatticesTrilinearWeights) {
  const std::vector<glm::vec3>& at = session_->light_probes()->position;
  const ProbeLattice& lattice = session_->light_probes()->volumes[0];
  // Between lattice points 0.25 apart: fractions 0.25, 0.5 and 0.75 of a spacing.
  const glm::vec3 origin(-0.5f, 1.25f, -0.5f);
  const glm::vec3 f(0.25f, 0.5f, 0.75f);
  const glm::vec3 point = origin + 0.25f * (glm::vec3(1.0f, 1.0f, 2.0f) + f);
  std::array<glm::vec3, kShCoefficients> sh{};
  const ProbeBlend b = session_->probe_sh_at(point, sh);
  ASSERT_EQ(b.count, 8u);
  EXPECT_EQ(b.stage, ProbeBlend::Stage::kTrilinear);
  for (std::size_t i = 0; i < b.count; ++i) {
    ASSERT_GE(b.probe[i], lattice.first);
    const glm::vec3 u = (at[b.probe[i]] - point) / 0.25f;  // -f or 1 - f per axis
    float w = 1.0f;
    for (int a = 0; a < 3; ++a) w *= u[a] > 0.0f ? f[a] : 1.0f - f[a];
    EXPECT_NEAR(b.weight[i], w, 1e-4f) << "probe " << b.probe[i];
  }
  // Outside the volume, the probes next to the surfaces light the point.
  const ProbeBlend low = session_->probe_sh_at(glm::vec3(0.0f, 0.9f, 0.8f), sh);
  ASSERT_GT(low.count, 0u);
  for (std::size_t i = 0; i < low.count; ++i) EXPECT_LT(low.probe[i], lattice.first);
}

// The volume's probes against the path tracer at their own positions, for
// the six axis normals (reference/probe_reference_error.h): as close as the
// probes next to the surfaces, whose bound is 0.08 on the Cornell box
// (tests/unit/test_light_probes.cpp), since both gather alike.
TEST_F(CornellVolume, ItsProbesAgreeWithThePathTracer) {
  const LightProbes& probes = *session_->light_probes();
  const ProbeLattice& lattice = probes.volumes[0];
  std::vector<glm::vec3> all_sh, positions, sh;
  session_->probe_sh(all_sh);
  for (std::size_t p = lattice.first; p < lattice.first + lattice.count; ++p) {
    positions.push_back(probes.position[p]);
    sh.insert(sh.end(), all_sh.begin() + static_cast<std::ptrdiff_t>(p * kShCoefficients),
              all_sh.begin() + static_cast<std::ptrdiff_t>((p + 1) * kShCoefficients));
  }
  ReferenceSettings rs;
  rs.samples = 8192;
  const ReferencePathTracer reference(session_->tracer(), rs);
  const ProbeReferenceError e = probe_reference_error(reference, positions, sh, 25);
  std::printf(
      "Cornell box volume: %zu of %zu probes against the path tracer: relative RMSE %.4f "
      "(reference noise %.4f, without it %.4f), level %.4f\n",
      e.probes_measured, positions.size(), e.relative_rmse, e.reference_noise,
      e.noise_corrected_rmse, e.level);
  EXPECT_LT(e.noise_corrected_rmse, 0.08);
  EXPECT_NEAR(e.level, 1.0, 0.03);
}

// Walking across the box at mid height, through the volume and out of it
// on both sides, 1 cm at a time: the light an object gets changes smoothly
// between the volume's outer probes (x from -0.5 to 0.5), in the half cell
// beyond them where the volume fades out and the probes next to the
// surfaces fade in, and beyond, where those probes alone light it (mid-air
// between walls: their wider tent and nearest-probe stages). Measured: the
// largest step between neighbouring points in each part, against the
// walk's mean level.
TEST_F(CornellVolume, TheLightStepsLittleWhereTheVolumeEnds) {
  std::array<glm::vec3, kShCoefficients> sh{};
  double level = 0.0, step[3] = {0.0, 0.0, 0.0};  // inside, fading, outside
  glm::vec3 last(0.0f);
  int points = 0;
  for (int i = 0; i <= 180; ++i) {
    const float x = -0.9f + 0.01f * static_cast<float>(i);
    const glm::vec3 at(x, 1.5f, 0.05f);
    const ProbeBlend b = session_->probe_sh_at(at, sh);
    ASSERT_GT(b.count, 0u) << x;
    glm::vec3 e(0.0f);
    for (std::size_t k = 0; k < 6; ++k) e += sh_irradiance(sh.data(), probe_directions()[k]);
    e /= 6.0f;
    level += (e.x + e.y + e.z) / 3.0;
    if (i > 0) {
      // The part of the step's midpoint (1 mm off the edges at 0.5 and 0.625).
      const float mid = std::abs(x - 0.005f);
      const int part = mid < 0.5f ? 0 : mid < 0.625f ? 1 : 2;
      const glm::vec3 d = glm::abs(e - last);
      step[part] = std::max<double>({step[part], d.x, d.y, d.z});
    }
    last = e;
    ++points;
  }
  level /= points;
  std::printf(
      "Across the volume's edge, 1 cm steps: mean level %.4g; largest step %.2f%% of it "
      "between the volume's probes, %.2f%% where it fades out, %.2f%% beyond\n",
      level, 100.0 * step[0] / level, 100.0 * step[1] / level, 100.0 * step[2] / level);
  ASSERT_GT(level, 0.0);
  // Trilinear between probes 25 cm apart, and a fade over 12.5 cm: no
  // step of more than a few percent of the level.
  EXPECT_LT(step[0], 0.05 * level);
  EXPECT_LT(step[1], 0.05 * level);
}

TEST(ProbeVolumeErrors, AreRefusedBeforeTracingNamingTheSetting) {
  const Scene scene = cornell();
  const auto bake_error = [&](const BakeSettings& s) {
    return error_of([&] {
      Diagnostics d;
      Progress progress;
      Baker(scene, s, d).run(progress);
    });
  };
  // Outside the scene's bounds.
  std::string e = bake_error(volume_settings(ProbePlacementMode::On, "5,5,5,6,6,6,0.5"));
  EXPECT_TRUE(contains(e, "light_probe_volumes") && contains(e, "outside")) << e;
  // 8e15 probes: refused at once, before any memory for them.
  const auto start = std::chrono::steady_clock::now();
  e = bake_error(volume_settings(ProbePlacementMode::On, "-1,0,-1,1,2,1,0.00001"));
  EXPECT_TRUE(contains(e, "light_probe_volumes") && contains(e, "light_probes_max")) << e;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
  // Each volume fits, together with the surfaces' candidates they do not.
  BakeSettings s = volume_settings(ProbePlacementMode::On, kVolume);
  s.light_probes_max = 120;
  e = bake_error(s);
  EXPECT_TRUE(contains(e, "light_probes_max")) << e;
  // A zero spacing, and 'volumes' without any volume.
  EXPECT_TRUE(contains(bake_error(volume_settings(ProbePlacementMode::On, "0,0,0,1,1,1,0")),
                       "light_probe_volumes"));
  EXPECT_TRUE(
      contains(bake_error(volume_settings(ProbePlacementMode::VolumesOnly, "")), "light_probes"));
}

TEST(ProbeVolumePlacement, AutoOverTheLimitKeepsTheVolumesAndSaysWhy) {
  const Scene scene = cornell();
  BakeSettings s = volume_settings(ProbePlacementMode::Auto, kVolume);
  s.light_probes_max = 120;  // the volume's 75 fit, the surfaces' candidates do not
  Diagnostics d;
  Progress progress;
  const BakeResult r = Baker(scene, s, d).run(progress);
  EXPECT_FALSE(r.probe_placement.surfaces);
  EXPECT_TRUE(contains(r.probe_placement.surfaces_skipped, "light_probes_max"));
  EXPECT_EQ(r.light_probes.size(), kVolumeProbes);
  bool warned = false;
  for (const Diagnostic& w : d.warnings()) warned |= contains(w.message, "light_probes_max");
  EXPECT_TRUE(warned);
  // Volumes only: no probe next to the surfaces even under the limit.
  const BakeResult only =
      Baker(scene, volume_settings(ProbePlacementMode::VolumesOnly, kVolume), d).run(progress);
  EXPECT_EQ(only.light_probes.size(), kVolumeProbes);
  EXPECT_EQ(only.light_probes.volumes[0].first, 0u);
}

TEST(ProbeVolumeFiles, ADamagedVolumeFileIsOneErrorNamingIt) {
  test::ScratchDir dir("bounce-probe-volumes");
  const Scene scene = cornell();
  Diagnostics d;
  Progress progress;
  const BakeResult r =
      Baker(scene, volume_settings(ProbePlacementMode::On, kVolume), d).run(progress);
  const std::filesystem::path bake = dir.path() / "bake";
  write_bake(bake, scene, r, d);
  const auto read = [&] {
    return read_light_probes(bake, r.patches.size(), r.samples.samples.size());
  };
  ASSERT_EQ(read()->volumes.size(), 1u);
  const std::filesystem::path file = bake / bake_file::kProbeVolumes;
  const NpyArray<float> good = read_npy_f32(file);
  const auto damaged = [&](std::size_t column, float value) {
    std::vector<float> v = good.data;
    v[column] = value;
    write_npy(file, v, {1, 9});
    const std::string e = error_of([&] { read(); });
    EXPECT_TRUE(contains(e, bake_file::kProbeVolumes)) << column << " = " << value << ": " << e;
  };
  damaged(3, 0.0f);                                    // spacing
  damaged(3, std::nanf(""));                           // spacing
  damaged(0, std::numeric_limits<float>::infinity());  // origin
  damaged(4, 0.0f);                                    // cells
  damaged(5, 2.5f);                                    // cells, not whole
  damaged(7, good.data[7] + 1.0f);                     // first: a gap before the volume
  damaged(8, good.data[8] + 1.0f);                     // count: past the probes
  damaged(8, good.data[8] - 1.0f);                     // count: probes after the last volume
  write_npy(file, good.data, {9});
  EXPECT_TRUE(contains(error_of([&] { read(); }), bake_file::kProbeVolumes));
}

}  // namespace
}  // namespace bounce
