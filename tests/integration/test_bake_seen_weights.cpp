// The seen weights of a bake's final gather (gather_seen_*.npy,
// runtime/seen_first_hit.h) read back onto the patches, and a damaged file
// is one error naming it: never a crash, never weights that point at the
// samples of another patch.
#include <cmath>
#include <span>

#include "bake/bake_reader.h"
#include "cli_harness.h"
#include "io/npy.h"

namespace bounce::itest {
namespace {

class SeenWeights : public ::testing::Test {
 protected:
  void SetUp() override {
    out = tmp.path() / "bake";
    const RunResult r = run({"bake", scene("cornell-box"), "--voxel", "4", "--codec", "dense",
                             "--quiet", "--out", out.string()},
                            tmp.path());
    ASSERT_EQ(r.exit_code, 0) << r;
  }
  // `bounce solve` on the bake: exit 1 and one error naming `file`.
  void expect_solve_refuses(const std::string& file, const std::string& problem) {
    const RunResult r =
        run({"solve", out.string(), "--no-images", "--no-mesh", "--quiet"}, tmp.path());
    EXPECT_EQ(r.exit_code, 1) << r;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(problem), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out / "solve")) << "a refused bake left a half-written solve";
  }
  TempDir tmp;
  fs::path out;
};

TEST_F(SeenWeights, ReadBackOntoEachPatchsMembers) {
  const LoadedBake b = BakeReader::read(out);
  ASSERT_EQ(b.patches.member_seen_weight.size(), b.patches.member_samples.size());
  const auto first = read_npy_u32(out / "gather_seen_first.npy");
  const auto sample = read_npy_u32(out / "gather_seen_sample.npy");
  const auto weight = read_npy_f32(out / "gather_seen_weight.npy");
  ASSERT_EQ(first.data.size(), b.patches.size() + 1);
  std::size_t rows = 0;
  for (std::size_t p = 0; p < b.patches.size(); ++p) {
    double total = 0.0, on_members = 0.0;
    for (std::uint32_t k = first.data[p]; k < first.data[p + 1]; ++k) total += weight.data[k];
    for (std::uint32_t m = b.patches.member_first[p]; m < b.patches.member_first[p + 1]; ++m)
      on_members += b.patches.member_seen_weight[m];
    EXPECT_NEAR(on_members, total, 1e-6) << "patch " << p;
    if (first.data[p + 1] > first.data[p]) {
      ++rows;
      EXPECT_NEAR(total, 1.0, 1e-5) << "patch " << p << "'s shares";
    }
  }
  EXPECT_GT(rows, b.patches.size() / 2) << "most of the box's patches are seen by its vertices";
  EXPECT_EQ(sample.data.size(), weight.data.size());
  // The manifest says how many.
  const json seen = read_manifest(out).at("final_gather").at("seen_weights");
  EXPECT_EQ(seen.at("patches").get<std::size_t>(), rows);
  EXPECT_EQ(seen.at("entries").get<std::size_t>(), sample.data.size());
}

TEST_F(SeenWeights, SampleOfAnotherPatchIsOneErrorNamingTheFile) {
  const auto first = read_npy_u32(out / "gather_seen_first.npy");
  auto sample = read_npy_u32(out / "gather_seen_sample.npy");
  const LoadedBake b = BakeReader::read(out);
  // The first row's first sample swapped for a sample of the last patch.
  std::size_t p = 0;
  while (first.data[p] == first.data[p + 1]) ++p;
  const std::size_t last = b.patches.size() - 1;
  ASSERT_NE(p, last);
  sample.data[first.data[p]] = b.patches.member_samples[b.patches.member_first[last]];
  write_npy(out / "gather_seen_sample.npy", std::span<const std::uint32_t>(sample.data),
            sample.shape);
  try {
    BakeReader::read(out);
    FAIL() << "weights on another patch's sample were read";
  } catch (const BakeReader::ReadError& e) {
    EXPECT_NE(std::string(e.what()).find("gather_seen_first.npy"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not one of its members"), std::string::npos) << e.what();
  }
  expect_solve_refuses("gather_seen_first.npy", "not one of its members");
}

TEST_F(SeenWeights, WeightsOfAnotherLengthOrNotFiniteAreRefused) {
  auto weight = read_npy_f32(out / "gather_seen_weight.npy");
  ASSERT_GT(weight.data.size(), 1u);
  const auto shorter = std::span<const float>(weight.data).first(weight.data.size() - 1);
  write_npy(out / "gather_seen_weight.npy", shorter, {shorter.size()});
  EXPECT_THROW(BakeReader::read(out), BakeReader::ReadError);
  expect_solve_refuses("gather_seen_weight.npy", "");
  weight.data[0] = std::nanf("");
  write_npy(out / "gather_seen_weight.npy", std::span<const float>(weight.data), weight.shape);
  expect_solve_refuses("gather_seen_first.npy", "outside [0, 1]");
}

}  // namespace
}  // namespace bounce::itest
