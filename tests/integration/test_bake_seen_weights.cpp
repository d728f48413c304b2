// The seen weights of a bake's final gather (gather_seen_*.npy,
// runtime/seen_first_hit.h) read back onto the patches, and its spots
// (gather_spot_*.npy, runtime/final_gather.h) with the gather; a damaged
// file is one error naming it: never a crash, never weights that point at
// the samples of another patch, never a count that sizes memory beyond what
// the bake holds.
#include <cmath>
#include <span>

#include "cli_harness.h"
#include "folder/bake_reader.h"
#include "folder/final_gather_files.h"
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

TEST_F(SeenWeights, SpotsReadBackWithTheGather) {
  const LoadedBake b = BakeReader::read(out);
  const std::optional<FinalGather> g = read_final_gather(out, b.size(), b.samples.samples.size());
  ASSERT_TRUE(g.has_value());
  ASSERT_EQ(g->spot_first.size(), b.samples.samples.size() + 1);
  ASSERT_GT(g->spots(), 0u);
  std::size_t with_spots = 0;
  for (std::size_t s = 0; s < b.samples.samples.size(); ++s) {
    with_spots += g->spot_first[s + 1] > g->spot_first[s] ? 1 : 0;
    for (std::uint32_t k = g->spot_first[s]; k < g->spot_first[s + 1]; ++k)
      EXPECT_EQ(g->near.patch[g->spot_base() + k], static_cast<std::uint32_t>(b.patch_of_sample[s]))
          << "sample " << s;
  }
  const json spots = read_manifest(out).at("final_gather").at("spots");
  EXPECT_EQ(spots.at("samples").get<std::size_t>(), with_spots);
  EXPECT_EQ(spots.at("points").get<std::size_t>(), g->spots());
}

TEST_F(SeenWeights, SpotsOfAnotherLengthOrWeightAreRefused) {
  auto first = read_npy_u32(out / "gather_spot_first.npy");
  const auto shorter = std::span<const std::uint32_t>(first.data).first(first.data.size() - 1);
  write_npy(out / "gather_spot_first.npy", shorter, {shorter.size()});
  expect_solve_refuses("gather_spot_first.npy", "one row start per sample");
  write_npy(out / "gather_spot_first.npy", std::span<const std::uint32_t>(first.data), first.shape);
  auto weight = read_npy_f32(out / "gather_spot_weight.npy");
  ASSERT_GT(weight.data.size(), 1u);
  weight.data[0] = 2.0f;
  write_npy(out / "gather_spot_weight.npy", std::span<const float>(weight.data), weight.shape);
  expect_solve_refuses("gather_*.npy", "spot weight outside [0, 1]");
}

// Found by the bake-folder fuzz target: the number of clusters is the largest
// one named plus one, and every frame sizes its light buffer by it, so one
// damaged entry (0xF3F3F3F3) asked for 65 GB. Dense numbering, each cluster
// at least one patch: more clusters than patches is damage.
TEST_F(SeenWeights, AClusterBeyondThePatchCountIsRefused) {
  auto cluster = read_npy_u32(out / "gather_cluster.npy");
  ASSERT_GT(cluster.data.size(), 1u);
  cluster.data[0] = 0xF3F3F3F3u;
  write_npy(out / "gather_cluster.npy", std::span<const std::uint32_t>(cluster.data),
            cluster.shape);
  expect_solve_refuses("gather_cluster.npy", "patches make at most that many clusters");
}

}  // namespace
}  // namespace bounce::itest
