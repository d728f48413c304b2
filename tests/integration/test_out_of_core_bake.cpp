// An out-of-core bake (--out-of-core on: F, T and the transport's work
// buffers in memory-mapped temporary files) is the in-memory bake bit for
// bit: the same bake run both ways must leave byte-identical F.npy, T.npy
// and compressed files and the same numbers in the manifest, and no
// temporary file behind. A folder that cannot hold the files is one error
// naming it, and no bake folder. Both runs use OpenBLAS: --gemm auto picks
// a backend by timing, a loaded machine may pick CLBlast for one run only,
// and the backends round differently.
#include "cli_harness.h"

namespace bounce::itest {
namespace {

// The manifest without what legitimately differs between two runs: times
// (and the GEMM backend's reason, which quotes one), memory, the out-of-core
// setting and decision itself.
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
  // The GEMM backend's reason quotes a timed product.
  for (json& d : m["transport"]["decisions"])
    if (d["what"].get<std::string>().rfind("GEMM backend", 0) == 0) d.erase("why");
  return m;
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
    const RunResult r = run(args, tmp.path());
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
