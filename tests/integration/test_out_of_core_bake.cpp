// An out-of-core bake (--out-of-core on: F, T and the transport's work
// buffers in memory-mapped temporary files) is the in-memory bake bit for
// bit: the same bake run both ways must leave byte-identical F.npy, T.npy
// and compressed files and the same numbers in the manifest, and no
// temporary file behind. A folder that cannot hold the files is one error
// naming it, and no bake folder. Both runs use OpenBLAS and the same
// OpenBLAS kernels: --gemm auto picks a backend by timing, and where OpenBLAS
// does not know the CPU its kernels are picked by timing too, so a loaded
// machine may pick differently for one run only, and the choices round
// differently.
#include "cli_harness.h"

namespace bounce::itest {
namespace {

// The manifest without what legitimately differs between two runs: times
// (and the GEMM backend's reason, which quotes one), memory, the out-of-core
// setting and decision itself.
constexpr const char* kKernels = "OpenBLAS kernels: ";

json comparable(json m) {
  m.erase("stages");
  m.erase("total_seconds");
  m.erase("memory");
  m["settings"]["requested"].erase("out_of_core");
  m["settings"]["resolved"].erase("out_of_core");
  std::function<void(json&)> strip = [&](json& j) {
    if (j.is_object()) {
      for (const char* key : {"seconds", "probe_openblas_seconds", "probe_clblast_seconds"})
        j.erase(key);
      for (auto& [key, value] : j.items())
        if (key != "stage_seconds") strip(value);
      j.erase("stage_seconds");
    } else if (j.is_array()) {
      for (json& v : j) strip(v);
    }
  };
  strip(m);
  // The GEMM backend's and the kernels' reasons quote a timed product, or
  // the environment that pinned the kernels.
  for (json& d : m["transport"]["decisions"]) {
    const std::string what = d["what"].get<std::string>();
    if (what.rfind("GEMM backend", 0) == 0 || what.rfind(kKernels, 0) == 0) d.erase("why");
  }
  return m;
}

// The OpenBLAS kernels a bake used, from its manifest's decisions; empty
// when it records none.
std::string kernels_used(const json& manifest) {
  for (const json& d : manifest["transport"]["decisions"]) {
    const std::string what = d["what"].get<std::string>();
    if (what.rfind(kKernels, 0) == 0) return what.substr(std::string(kKernels).size());
  }
  return {};
}

struct Case {
  const char* name;
  std::vector<std::string> args;
};

class OutOfCoreBake : public ::testing::TestWithParam<Case> {};

TEST_P(OutOfCoreBake, IsBitIdenticalToTheInMemoryBake) {
  TempDir tmp;
  const fs::path matrices = tmp / "matrices";
  fs::create_directories(matrices);
  std::map<std::string, fs::path> out;
  for (const std::string mode : {"off", "on"}) {
    out[mode] = tmp / ("bake-" + mode);
    std::vector<std::string> args = {"bake",
                                     scene("cornell-box"),
                                     "--voxel",
                                     "4",
                                     "--dump-matrices",
                                     "--no-pictures",
                                     "--quiet",
                                     "--out-of-core",
                                     mode,
                                     "--out-of-core-dir",
                                     matrices.string(),
                                     "--gemm",
                                     "openblas",
                                     "--out",
                                     out[mode].string()};
    args.insert(args.end(), GetParam().args.begin(), GetParam().args.end());
    RunOptions options;
    options.cwd = tmp.path();
    // The second run uses the kernels the first one chose.
    if (mode == "on") {
      const std::string kernels = kernels_used(read_manifest(out["off"]));
      if (!kernels.empty()) options.env["OPENBLAS_CORETYPE"] = kernels;
    }
    const RunResult r = run(args, options);
    ASSERT_EQ(r.exit_code, 0) << r;
  }
  const json on = read_manifest(out["on"]), off = read_manifest(out["off"]);
  EXPECT_TRUE(on["memory"]["out_of_core"].get<bool>());
  EXPECT_FALSE(off["memory"]["out_of_core"].get<bool>());
  EXPECT_EQ(on["memory"]["matrix_dir"], matrices.string());
  // The temporary files were unlinked when mapped: nothing left behind.
  EXPECT_TRUE(fs::is_empty(matrices));

  std::size_t compared = 0;
  for (const auto& entry : fs::directory_iterator(out["off"])) {
    const std::string name = entry.path().filename().string();
    if (name == "manifest.json") continue;
    ASSERT_TRUE(fs::exists(out["on"] / name)) << name;
    EXPECT_TRUE(read_text(entry.path()) == read_text(out["on"] / name)) << name << " differs";
    ++compared;
  }
  EXPECT_TRUE(fs::exists(out["off"] / "F.npy"));
  EXPECT_TRUE(fs::exists(out["off"] / "T.npy"));
  EXPECT_GE(compared, 4u);
  EXPECT_EQ(comparable(on), comparable(off));
}

INSTANTIATE_TEST_SUITE_P(
    Transports, OutOfCoreBake,
    ::testing::Values(Case{"LU_compressed", {"--bounces", "inf", "--codec", "ours"}},
                      Case{"Doubling_dense", {"--bounces", "6", "--codec", "dense"}}),
    [](const ::testing::TestParamInfo<Case>& param_info) {
      return std::string(param_info.param.name);
    });

TEST(OutOfCoreBakeErrors, AFolderThatCannotHoldTheMatricesIsNamedAndNothingIsWritten) {
  TempDir tmp;
  const fs::path missing = tmp / "no-such-folder";
  const fs::path out = tmp / "bake";
  const RunResult r = run({"bake", scene("cornell-box"), "--voxel", "4", "--quiet", "--out-of-core",
                           "on", "--out-of-core-dir", missing.string(), "--out", out.string()},
                          tmp.path());
  EXPECT_NE(r.exit_code, 0) << r;
  EXPECT_TRUE(contains(r.err, missing.string())) << r;
  EXPECT_TRUE(contains(r.err, "temporary matrix file")) << r;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(hidden_leftovers(out).empty());
}

}  // namespace
}  // namespace bounce::itest
