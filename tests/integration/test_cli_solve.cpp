// `bounce solve` on a real bake: the three ways of computing T b agree (the
// compressed ones to float rounding, or bfloat16 rounding for the default C++
// loop, the dense one within the compression error the bake measured),
// lights move, outputs are complete, bad input is named.
#include "cli_harness.h"
#include "solve_fixture.h"

namespace bounce::itest {
namespace {

// Area-weighted relative L2 difference of the indirect light (slot 2).
double indirect_difference(const NpyArray<float>& a, const NpyArray<float>& b,
                           const NpyArray<float>& patches) {
  double diff = 0.0, ref = 0.0;
  for (std::size_t p = 0; p < a.shape[0]; ++p)
    for (std::size_t k = 0; k < 3; ++k) {
      const double w = at(patches, p, 6);
      const double x = a.data[p * 9 + 6 + k], y = b.data[p * 9 + 6 + k];
      diff += w * (x - y) * (x - y);
      ref += w * y * y;
    }
  return std::sqrt(diff / ref);
}

TEST_F(Solve, OpenClCppAndDenseAgree) {
  json s_cl, s_cpp, s_bf16, s_dense;
  const auto cl = solve("cl", {"--multiply", "opencl", "--no-images", "--no-mesh"}, &s_cl);
  const auto cpp =
      solve("cpp", {"--multiply", "cpp", "--float32", "--no-images", "--no-mesh"}, &s_cpp);
  const auto bf16 = solve("bf16", {"--multiply", "cpp", "--no-images", "--no-mesh"}, &s_bf16);
  const auto dense = solve("dense", {"--multiply", "dense", "--no-images", "--no-mesh"}, &s_dense);
  EXPECT_TRUE(contains(s_cl["multiply"].get<std::string>(), "OpenCL")) << s_cl["multiply"];
  EXPECT_TRUE(contains(s_cpp["multiply"].get<std::string>(), "C++")) << s_cpp["multiply"];
  EXPECT_TRUE(contains(s_dense["multiply"].get<std::string>(), "dense")) << s_dense["multiply"];
  const auto patches = read_npy_f32(bake / "patches.npy");
  const auto n = patches.shape[0];
  ASSERT_EQ(cl.shape, (std::vector<std::size_t>{n, 3, 3}));
  // Same direct light whatever the multiply.
  for (std::size_t k = 0; k < n * 9; k += 9)
    for (std::size_t c = 0; c < 6; ++c) ASSERT_EQ(cl.data[k + c], dense.data[k + c]);
  // Same compressed matrix, other summation order: float rounding only.
  EXPECT_LT(indirect_difference(cl, cpp, patches), 1e-5);
  // The default C++ loop: bfloat16 where the CPU has it, each row within
  // 2^-8 of sum |T||b| (the unit tests' bound; T and b are non-negative
  // here, so within 2^-8 relative), else the float32 loop itself.
  const double rounding = indirect_difference(bf16, cpp, patches);
  EXPECT_LT(rounding, std::ldexp(1.0, -8)) << s_bf16["multiply"];
  if (contains(s_bf16["multiply"].get<std::string>(), "bf16")) {
    EXPECT_GT(rounding, 0.0);
  }
  // Against the exact matrix: the error compression adds. The bake measured
  // it per evaluation light (the scene's point light and the area light are
  // among them); the sum of two lights' errors is at most twice the worst.
  const double worst =
      read_manifest(bake)["compression"]["errors"]["indirect_light"]["rel_rms_max"].get<double>();
  const double d = indirect_difference(cpp, dense, patches);
  EXPECT_GT(d, 0.0) << "compressed equals exact: suspicious";
  EXPECT_LT(d, 2.0 * worst) << "compressed vs dense " << d << ", bake's worst light " << worst;
  double indirect = 0.0;
  for (std::size_t k = 0; k < n * 9; k += 9) indirect += dense.data[k + 6];
  EXPECT_GT(indirect, 0.0);
}

TEST_F(Solve, MovingTheLightChangesTheDirectLightAndOutputsAreComplete) {
  json summary;
  const auto here = solve("here", {"--no-mesh", "--no-images"});
  const auto moved =
      solve("moved", {"--light", "ceiling-point:-0.7,0.3,0.2", "--width", "64", "--height", "48"},
            &summary);
  double changed = 0.0;
  for (std::size_t k = 0; k < here.data.size(); ++k)
    changed += std::abs(here.data[k] - moved.data[k]);
  EXPECT_GT(changed, 0.0);
  EXPECT_EQ(summary["lights"][0]["position"], json::array({-0.7f, 0.3f, 0.2f}));
  const fs::path out = tmp->path() / "moved";
  for (const char* f : {"lit.ply", "camera_full.png", "camera_full.exr", "camera_direct.png",
                        "camera_indirect.exr"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  EXPECT_EQ(read_text(out / "lit.ply").rfind("ply\nformat binary_little_endian 1.0", 0), 0u);
}

TEST_F(Solve, BadLightAndMissingBakeAreNamed) {
  const RunResult r1 = run({"solve", bake.string(), "--light", "sun:0,1,0", "--no-images",
                            "--no-mesh", "--out", (tmp->path() / "bad").string()},
                           tmp->path());
  EXPECT_EQ(r1.exit_code, 1) << r1;
  EXPECT_TRUE(contains(r1.err, "sun") && contains(r1.err, "ceiling-point")) << r1;
  const RunResult r2 =
      run({"solve", bake.string(), "--light", "ceiling-point:1,2", "--no-images"}, tmp->path());
  EXPECT_EQ(r2.exit_code, 1) << r2;
  EXPECT_TRUE(contains(r2.err, "NAME:x,y,z")) << r2;
  const RunResult r3 = run({"solve", (tmp->path() / "nothing").string()}, tmp->path());
  EXPECT_EQ(r3.exit_code, 1) << r3;
  EXPECT_TRUE(contains(r3.err, "nothing")) << r3;
}

// A damaged bake folder: one clear error naming the damaged file, exit 1,
// never a crash or a hang.
struct Damage {
  const char* name;
  const char* file;  // the file damaged, which the error must name
  void (*apply)(const fs::path& bake);
};

void PrintTo(const Damage& d, std::ostream* os) { *os << d.name; }

class SolveDamagedBake : public Solve, public ::testing::WithParamInterface<Damage> {};

TEST_P(SolveDamagedBake, OneErrorNamingTheFile) {
  const Damage& d = GetParam();
  const fs::path copy = tmp->path() / (std::string("damaged-") + d.name);
  fs::remove_all(copy);
  fs::copy(bake, copy, fs::copy_options::recursive);
  d.apply(copy);
  const RunResult r = run({"solve", copy.string(), "--no-images", "--no-mesh", "--out",
                           (tmp->path() / (std::string("out-") + d.name)).string()},
                          tmp->path(), 60.0);
  EXPECT_EQ(r.exit_code, 1) << r;
  const auto errors = lines_starting_with(r.err, "bounce: error: ");
  ASSERT_EQ(errors.size(), 1u) << r;
  EXPECT_TRUE(contains(errors[0], d.file)) << errors[0];
}

void truncate_file(const fs::path& path, std::uintmax_t keep) { fs::resize_file(path, keep); }

INSTANTIATE_TEST_SUITE_P(
    Damages, SolveDamagedBake,
    ::testing::Values(Damage{"truncated_dds", "T.dds",
                             [](const fs::path& b) { truncate_file(b / "T.dds", 200); }},
                      Damage{"dds_header_only", "T.dds",
                             [](const fs::path& b) { truncate_file(b / "T.dds", 60); }},
                      Damage{"missing_permutation", "permutation.npy",
                             [](const fs::path& b) { fs::remove(b / "permutation.npy"); }},
                      Damage{"permutation_wrong_shape", "permutation.npy",
                             [](const fs::path& b) {
                               const auto p = read_npy_u32(b / "permutation.npy");
                               std::vector<std::uint32_t> half(p.data.begin(),
                                                               p.data.begin() + p.data.size() / 2);
                               write_npy(b / "permutation.npy", half, {half.size()});
                             }},
                      Damage{"patches_wrong_dtype", "patches.npy",
                             [](const fs::path& b) {
                               const auto p = read_npy_f32(b / "patches.npy");
                               std::vector<std::int32_t> ints(p.data.size(), 0);
                               write_npy(b / "patches.npy", ints, p.shape);
                             }},
                      Damage{
                          "truncated_kept_values", "T_kept_0_value.npy",
                          [](const fs::path& b) { truncate_file(b / "T_kept_0_value.npy", 100); }},
                      Damage{"manifest_not_json", "manifest.json",
                             [](const fs::path& b) {
                               write_text(b / "manifest.json", "{\"format\": \"bounce-");
                             }},
                      Damage{"manifest_old_version", "manifest.json",
                             [](const fs::path& b) {
                               json m = read_manifest(b);
                               m["format_version"] = 1;
                               write_text(b / "manifest.json", m.dump());
                             }},
                      Damage{"manifest_missing_key", "manifest.json",
                             [](const fs::path& b) {
                               json m = read_manifest(b);
                               m["compression"].erase("quantizers");
                               write_text(b / "manifest.json", m.dump());
                             }},
                      Damage{"lights_missing", "lights_first_hit.npy",
                             [](const fs::path& b) { fs::remove(b / "lights_first_hit.npy"); }}),
    [](const ::testing::TestParamInfo<Damage>& p) { return std::string(p.param.name); });

// `solve` with the default --multiply auto takes every bake `bake` writes:
// a dense bake (T.npy, no T.dds) with its dense matrix, a compressed one with
// the compressed product.
class SolveAuto : public ::testing::TestWithParam<const char*> {};

TEST_P(SolveAuto, MultipliesWhatTheCodecStored) {
  const std::string codec = GetParam();
  TempDir tmp;
  const fs::path bake = tmp / "bake";
  const RunResult baked = run({"bake", scene("cornell-box"), "--voxel", "4", "--codec", codec,
                               "--no-pictures", "--quiet", "--out", bake.string()},
                              tmp.path(), 120.0);
  ASSERT_EQ(baked.exit_code, 0) << baked;
  ASSERT_EQ(fs::exists(bake / "T.dds"), codec != "dense");
  ASSERT_EQ(fs::exists(bake / "T.npy"), codec == "dense");
  auto solve = [&](const std::string& name, const std::vector<std::string>& extra) {
    std::vector<std::string> args{"solve",  bake.string(), "--no-images",        "--no-mesh",
                                  "--json", "--out",       (tmp / name).string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run(args, tmp.path(), 120.0);
    EXPECT_EQ(r.exit_code, 0) << r;
    return std::make_pair(parse_json(r.out), read_npy_f32(tmp / name / "patch_light.npy"));
  };
  const auto [summary, light] = solve("auto", {});
  const std::string multiply = summary.value("multiply", "");
  EXPECT_EQ(multiply.rfind(codec == "dense" ? "dense" : "compressed", 0), 0u) << multiply;
  // The indirect light (slot 2 of each patch) is there and finite.
  double indirect = 0.0;
  for (std::size_t p = 0; p < light.shape[0]; ++p)
    for (std::size_t k = 0; k < 3; ++k) {
      const float v = light.data[p * 9 + 6 + k];
      ASSERT_TRUE(std::isfinite(v)) << "patch " << p;
      indirect += v;
    }
  EXPECT_GT(indirect, 0.0);
  if (codec == "dense") {
    // auto on a dense bake is exactly the dense product asked for by name.
    const auto [named_summary, named] = solve("dense", {"--multiply", "dense"});
    EXPECT_EQ(light.data, named.data);
  }
}

INSTANTIATE_TEST_SUITE_P(Codecs, SolveAuto, ::testing::Values("dense", "paper", "ours"),
                         [](const ::testing::TestParamInfo<const char*>& p) {
                           return std::string(p.param);
                         });

}  // namespace
}  // namespace bounce::itest
