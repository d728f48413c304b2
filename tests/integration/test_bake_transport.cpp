// The multi-bounce matrix in a bake folder, checked from the outside: the
// compressed files are decoded here with independent code (libsquish's BC
// decoder, the paper's log formula written out, the CSR and permutation read
// from .npy) and compared with the exact T.npy, so the error figures of the
// manifest are recomputed rather than trusted; OpenImageIO must open the DDS.
#include <OpenImageIO/imageio.h>

#include <numeric>
#include <set>

#include "cli_harness.h"
#include "decoded_bake.h"
#include "folder/bake_reader.h"
#include "light_error_check.h"

namespace bounce::itest {
namespace {

class CompressedBake : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    out = tmp.path() / "bake";
    const RunResult r = run({"bake", scene("cornell-box"), "--voxel", "6", "--codec", GetParam(),
                             "--dump-matrices", "--quiet", "--out", out.string()},
                            tmp.path());
    ASSERT_EQ(r.exit_code, 0) << r;
    manifest = read_manifest(out);
    compression = manifest["compression"];
    exact = read_npy_f32(out / "T.npy");
  }
  TempDir tmp;
  fs::path out;
  json manifest, compression;
  NpyArray<float> exact;
};

TEST_P(CompressedBake, ManifestErrorsMatchAnIndependentDecodeOfTheFiles) {
  ASSERT_EQ(compression["codec"], GetParam());
  const Decoded d = decode_bake(out, compression);
  ASSERT_EQ(exact.shape, (std::vector<std::size_t>{d.channels.size(), d.n, d.n}));
  double sum = 0.0, max = 0.0, diff2 = 0.0, ref2 = 0.0;
  for (std::size_t c = 0; c < d.channels.size(); ++c)
    for (std::size_t k = 0; k < d.n * d.n; ++k) {
      const double e =
          std::abs(static_cast<double>(d.channels[c][k]) - exact.data[c * d.n * d.n + k]);
      sum += e;
      max = std::max(max, e);
      diff2 += e * e;
      ref2 += static_cast<double>(exact.data[c * d.n * d.n + k]) * exact.data[c * d.n * d.n + k];
    }
  const double count = static_cast<double>(d.channels.size() * d.n * d.n);
  const json& e = compression["errors"];
  // libsquish and our decoder agree bit for bit (unit tests); what remains is
  // float rounding of the log formula: well under 1e-4 relative.
  EXPECT_NEAR(e["sum_abs"].get<double>(), sum, 1e-4 * sum);
  EXPECT_NEAR(e["mean_abs"].get<double>(), sum / count, 1e-4 * sum / count);
  EXPECT_NEAR(e["max_abs"].get<double>(), max, 1e-4 * max);
  EXPECT_NEAR(e["rel_frobenius"].get<double>(), std::sqrt(diff2 / ref2),
              1e-4 * std::sqrt(diff2 / ref2));
  EXPECT_GT(sum, 0.0) << "compression that loses nothing is suspicious";
}

// The paper keeps the largest entries. Ours keeps, per channel, as many
// entries (zeros included) as the kept fraction says, chosen in a second pass
// by the error the first pass's blocks had there: exact values (the paper's)
// or their nearest halves (ours), the count right.
TEST_P(CompressedBake, KeptEntriesAreExactAndThePapersAreTheLargest) {
  const auto n = manifest["counts"]["patches"].get<std::size_t>();
  const int stored = compression["stored_channels"].get<int>();
  const bool paper = GetParam() == "paper";
  EXPECT_EQ(compression["kept_storage"], paper ? "float32" : "float16");
  EXPECT_EQ(compression["light_weighted"].get<bool>(), !paper);
  EXPECT_EQ(compression["kept_passes"].get<int>(), paper ? 1 : 2);
  for (int c = 0; c < stored; ++c) {
    const std::string base = "T_kept_" + std::to_string(c);
    const KeptFiles kf = read_kept_files(out, compression, c, n);
    const float* t = exact.data.data() + static_cast<std::size_t>(c) * n * n;
    std::vector<bool> kept(n * n, false);
    float smallest_kept = std::numeric_limits<float>::infinity();
    for (std::size_t i = 0; i < n; ++i)
      for (std::uint32_t k = kf.row_ptr[i]; k < kf.row_ptr[i + 1]; ++k) {
        ASSERT_LT(kf.col[k], n);
        const float v = t[i * n + kf.col[k]];
        if (paper)
          ASSERT_EQ(kf.value[k], v) << "kept entry not exact";
        else  // the nearest half: within 2^-11 of the value, or 2^-25 below the normals
          ASSERT_LE(std::abs(kf.value[k] - v), std::max(std::ldexp(v, -11), std::ldexp(1.0f, -25)))
              << "kept entry not the half of its value";
        ASSERT_FALSE(kept[i * n + kf.col[k]]) << "entry kept twice";
        kept[i * n + kf.col[k]] = true;
        smallest_kept = std::min(smallest_kept, kf.value[k]);
      }
    if (paper)
      for (std::size_t k = 0; k < n * n; ++k) {
        if (kept[k]) continue;
        ASSERT_LT(t[k], smallest_kept) << "a larger entry was not kept";
      }
    const double fraction = static_cast<double>(kf.value.size()) / static_cast<double>(n * n);
    EXPECT_NEAR(fraction, compression["kept_fraction"].get<double>(), 0.01);
  }
}

// The light error the manifest reports (and the budget was held to) is what
// T.npy, the decoded T.dds and the light vectors give.
TEST_P(CompressedBake, ManifestLightErrorMatchesARecomputationFromTheFiles) {
  const RecomputedLightError r = recompute_light_error_of_bake(out, manifest);
  const json& li = compression["errors"]["indirect_light"];
  EXPECT_EQ(li["lights"].get<std::size_t>(), r.lights);
  EXPECT_GT(r.lights, 4u) << "the scene's light and the four point lights at least";
  // The decoders differ by float rounding of the log formula (~5e-6 of each
  // entry), a few 1e-4 of an error of a few percent at most.
  EXPECT_NEAR(li["rel_rms_mean"].get<double>(), r.mean, 1e-3 * r.mean);
  EXPECT_NEAR(li["rel_rms_max"].get<double>(), r.max, 1e-3 * r.max);
  if (compression["error_budget"].is_number()) {
    EXPECT_EQ(compression["error_budget_metric"], "errors.indirect_light.rel_rms_max");
    if (compression["error_budget_met"].get<bool>())
      EXPECT_LE(r.max, compression["error_budget"].get<double>() * (1.0 + 1e-3));
    else
      EXPECT_GT(r.max, compression["error_budget"].get<double>() * (1.0 - 1e-3));
  }
}

TEST_P(CompressedBake, PermutationIsABijection) {
  const auto perm = read_npy_u32(out / "permutation.npy");
  const auto n = manifest["counts"]["patches"].get<std::size_t>();
  ASSERT_EQ(perm.data.size(), n);
  std::set<std::uint32_t> seen(perm.data.begin(), perm.data.end());
  EXPECT_EQ(seen.size(), n);
  EXPECT_EQ(*seen.rbegin(), n - 1);
}

TEST_P(CompressedBake, OpenImageIoOpensTheDds) {
  auto in = OIIO::ImageInput::open((out / "T.dds").string());
  ASSERT_TRUE(in) << OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  const auto padded = compression["padded_size"].get<int>();
  EXPECT_EQ(spec.width, padded);
  EXPECT_EQ(spec.height, padded);
  EXPECT_GE(spec.nchannels, 3) << "a colour scene's matrix is BC1 (RGB)";
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(spec.width) * spec.height *
                                   spec.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data()))
      << in->geterror();
  EXPECT_GT(std::accumulate(pixels.begin(), pixels.end(), 0.0), 0.0);
}

TEST_P(CompressedBake, SizesAddUpAndCompressionPays) {
  const json& s = compression["sizes"];
  const auto n = manifest["counts"]["patches"].get<std::size_t>();
  EXPECT_EQ(s["dense_rgb_float32_bytes"].get<std::size_t>(), 3 * n * n * 4);
  EXPECT_EQ(s["stored_bytes"].get<std::size_t>(), s["sparse_bytes"].get<std::size_t>() +
                                                      s["block_bytes"].get<std::size_t>() +
                                                      s["permutation_bytes"].get<std::size_t>());
  EXPECT_EQ(s["block_bytes"].get<std::size_t>(), fs::file_size(out / "T.dds") - 128);
  // Kept entries: 8 bytes each in float32 (uint32 column, float value), 4 in
  // float16 (uint16 column, half value), plus each channel's row starts.
  std::size_t sparse = 0;
  for (int c = 0; c < compression["stored_channels"].get<int>(); ++c)
    sparse += (n + 1) * 4 +
              read_kept_files(out, compression, c, n).col.size() * (GetParam() == "paper" ? 8 : 4);
  EXPECT_EQ(s["sparse_bytes"].get<std::size_t>(), sparse);
  EXPECT_GT(s["ratio_to_dense_rgb"].get<double>(), 4.0);
  for (const char* picture : {"T.png", "T_reordered.png", "T_error.png", "T_error_blocks.png"})
    EXPECT_TRUE(fs::exists(out / picture)) << picture;
}

TEST_P(CompressedBake, ReadingTheBakeBackGivesTheSameMatrixAndErrors) {
  const LoadedBake b = BakeReader::read(out);
  ASSERT_TRUE(b.compressed.has_value());
  const auto n = manifest["counts"]["patches"].get<std::size_t>();
  ASSERT_EQ(b.size(), n);
  ASSERT_EQ(b.dense.size(), static_cast<std::size_t>(b.stored_channels));
  const Decoded d = decode_bake(out, compression);
  std::vector<float> mine(n * n);
  for (int c = 0; c < b.compressed->channels; ++c) {
    decompress_channel(*b.compressed, c, mine.data());
    // libsquish's decode through the paper's formula in double, against ours
    // in float: exp of an argument up to R = 25 rounded to float (2^-24
    // relative) is off by up to 25 * 2^-24 * a few, about 5e-6 relative.
    for (std::size_t k = 0; k < n * n; ++k)
      ASSERT_NEAR(mine[k], d.channels[static_cast<std::size_t>(c)][k],
                  1e-5f * d.channels[static_cast<std::size_t>(c)][k])
          << "entry " << k;
  }
  std::vector<const float*> exact_matrices;
  for (const auto& t : b.dense) exact_matrices.push_back(t.data());
  const CompressionErrors e = measure_compression(exact_matrices, *b.compressed, b.probe);
  EXPECT_NEAR(e.matrix.sum_abs, compression["errors"]["sum_abs"].get<double>(),
              1e-6 * e.matrix.sum_abs);
  const json& li = compression["errors"]["indirect_light"];
  EXPECT_NEAR(e.indirect.rel_rms_mean, li["rel_rms_mean"].get<double>(), 1e-6);
  EXPECT_EQ(e.indirect.lights, li["lights"].get<std::size_t>());
  // Members: every sample with a patch is a member of exactly that patch.
  EXPECT_EQ(b.patches.member_first.back(), b.patches.member_samples.size());
  EXPECT_GT(b.patches.member_samples.size(), n);
}

TEST_P(CompressedBake, ReadingABakeWithAMissingPartNamesTheFile) {
  fs::remove(out / "permutation.npy");
  try {
    BakeReader::read(out);
    FAIL() << "read a bake without its permutation";
  } catch (const Error& e) {
    EXPECT_TRUE(contains(e.what(), "permutation.npy")) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Codecs, CompressedBake, ::testing::Values("paper", "ours"),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

TEST(TransportBake, PaperCodecIsThePublishedPipeline) {
  TempDir tmp;
  const fs::path out = tmp / "bake";
  const RunResult r = run({"bake", scene("cornell-box"), "--voxel", "5", "--codec", "paper",
                           "--no-pictures", "--quiet", "--out", out.string()},
                          tmp.path());
  ASSERT_EQ(r.exit_code, 0) << r;
  const json c = read_manifest(out)["compression"];
  EXPECT_EQ(c["kept_fraction"], 0.04);
  EXPECT_EQ(c["ordering"], "paper-2-passes");
  EXPECT_EQ(c["format"], "BC1");
  EXPECT_TRUE(contains(c["encoder"].get<std::string>(), "squish")) << c["encoder"];
  EXPECT_FALSE(fs::exists(out / "T.png")) << "--no-pictures";
}

// The default budget, 2% relative RMS error of the indirect light on the
// worst evaluation light, is met by ours on the Cornell box within the size
// limit, by the smallest kept fraction that meets it; recomputed from the
// files, not read from the manifest.
TEST(TransportBake, LightBudgetHoldsOnTheCornellBox) {
  TempDir tmp;
  const fs::path out = tmp / "bake";
  const RunResult r = run({"bake", scene("cornell-box"), "--voxel", "10", "--codec", "ours",
                           "--dump-matrices", "--no-pictures", "--quiet", "--out", out.string()},
                          tmp.path(), 300.0);  // a hang guard: the budget's trials take a while
  ASSERT_EQ(r.exit_code, 0) << r;
  const json m = read_manifest(out);
  const json c = m["compression"];
  EXPECT_EQ(c["error_budget"].get<double>(), 0.02) << "the default budget";
  ASSERT_TRUE(c["error_budget_met"].get<bool>()) << c["error_budget_outcome"];
  EXPECT_TRUE(contains(c["error_budget_outcome"].get<std::string>(), "met")) << c;
  EXPECT_LE(c["sizes"]["stored_bytes"].get<std::size_t>(),
            c["size_limit_bytes"].get<std::size_t>());
  EXPECT_EQ(c["size_limit"].get<double>(), 0.125);
  // The search measures kept fractions on a sample of the rows, then
  // compresses the whole matrix: every whole trial below the chosen kept
  // fraction missed the budget, and the chosen one's light error is the
  // manifest's.
  const double kept = c["kept_fraction"].get<double>();
  const std::size_t patches = m["counts"]["patches"].get<std::size_t>();
  ASSERT_GE(patches, 512u) << "a smaller matrix is sampled whole";
  bool chosen_tried = false, sampled = false;
  for (const json& t : c["kept_fraction_trials"]) {
    const std::size_t rows = t["rows_measured"].get<std::size_t>();
    EXPECT_LE(rows, patches) << t;
    if (rows < patches) {
      sampled = true;
      continue;
    }
    if (t["kept_fraction"].get<double>() < kept) {
      EXPECT_GT(t["light_rel_rms_max"].get<double>(), 0.02) << t;
    }
    if (t["kept_fraction"].get<double>() == kept) {
      chosen_tried = true;
      EXPECT_EQ(t["light_rel_rms_max"], c["errors"]["indirect_light"]["rel_rms_max"]);
    }
  }
  EXPECT_TRUE(chosen_tried);
  EXPECT_TRUE(sampled) << "the search measured no kept fraction on a sample of rows";
  const RecomputedLightError e = recompute_light_error_of_bake(out, m);
  EXPECT_LE(e.max, 0.02 * (1.0 + 1e-3));
  // Both figures are kept: the matrix norm beside the light error.
  EXPECT_GT(c["errors"]["rel_frobenius"].get<double>(), 0.0);
}

// A budget no kept fraction within the size limit meets: the bake keeps the
// largest kept fraction that fits, and says so in a warning and the manifest.
TEST(TransportBake, UnreachableLightBudgetIsSaidPlainly) {
  TempDir tmp;
  const fs::path out = tmp / "bake";
  const RunResult r =
      run({"bake", scene("cornell-box"), "--voxel", "5", "--codec", "ours", "--error-budget",
           "0.0001", "--size-limit", "0.1", "--no-pictures", "--out", out.string()},
          tmp.path());
  ASSERT_EQ(r.exit_code, 0) << r;
  EXPECT_TRUE(contains(r.err, "error budget NOT met")) << r;
  EXPECT_TRUE(contains(r.err, "--size-limit")) << r;
  const json c = read_manifest(out)["compression"];
  EXPECT_FALSE(c["error_budget_met"].get<bool>());
  EXPECT_TRUE(contains(c["error_budget_outcome"].get<std::string>(), "NOT met")) << c;
  // The core names the setting, as Python knows it; the CLI printed its option.
  EXPECT_TRUE(contains(c["error_budget_outcome"].get<std::string>(), "'size_limit'")) << c;
  EXPECT_FALSE(contains(c["error_budget_outcome"].get<std::string>(), "--size-limit")) << c;
  EXPECT_GT(c["errors"]["indirect_light"]["rel_rms_max"].get<double>(), 0.0001);
  EXPECT_LE(c["sizes"]["stored_bytes"].get<std::size_t>(),
            c["size_limit_bytes"].get<std::size_t>());
  // The largest kept fraction that fits was the one kept: every trial fitted.
  double largest = 0.0;
  for (const json& t : c["kept_fraction_trials"])
    largest = std::max(largest, t["kept_fraction"].get<double>());
  EXPECT_EQ(c["kept_fraction"].get<double>(), largest);
}

TEST(TransportBake, GreyFurnaceStoresOneChannelAndMatchesTheAnalyticSeries) {
  // Albedo 0.5 everywhere in a closed box: each row of T(inf) = sum_h (rho F)^h
  // sums to rho/(1 - rho) = 1 (F's rows sum to 1 within ~1%).
  TempDir tmp;
  const fs::path out = tmp / "bake";
  const RunResult r = run({"bake", scene("furnace"), "--voxel", "6", "--bounces", "inf", "--codec",
                           "ours", "--dump-matrices", "--quiet", "--out", out.string()},
                          tmp.path());
  ASSERT_EQ(r.exit_code, 0) << r;
  const json m = read_manifest(out);
  EXPECT_EQ(m["transport"]["grey"], true);
  ASSERT_EQ(m["transport"]["channels"].size(), 1u);
  EXPECT_EQ(m["transport"]["channels"][0]["rgb"], "RGB");
  EXPECT_EQ(m["transport"]["channels"][0]["bounces"], "inf");
  EXPECT_EQ(m["transport"]["channel_of_rgb"], json::array({0, 0, 0}));
  EXPECT_EQ(m["compression"]["format"], "BC4") << "one grey channel: BC4";
  EXPECT_EQ(m["compression"]["stored_channels"], 1);
  const auto t = read_npy_f32(out / "T.npy");
  const auto n = m["counts"]["patches"].get<std::size_t>();
  ASSERT_EQ(t.shape, (std::vector<std::size_t>{1, n, n}));
  for (std::size_t p = 0; p < n; ++p) {
    double row = 0.0;
    for (std::size_t q = 0; q < n; ++q) row += t.data[p * n + q];
    // F rows within 1% of 1 amplify to 1/(1 - 0.5 * 1.01) - 1: 2% here.
    EXPECT_NEAR(row, 1.0, 0.03) << "row " << p;
  }
  auto in = OIIO::ImageInput::open((out / "T.dds").string());
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(in->spec().nchannels, 1) << "BC4 is one channel";
}

TEST(TransportBake, SmallMatrixStaysDenseAndSaysSo) {
  TempDir tmp;
  const fs::path out = tmp / "bake";
  const RunResult r = run({"bake", scene("parallel-squares"), "--voxel", "4", "--bounces", "3",
                           "--quiet", "--out", out.string()},
                          tmp.path());
  ASSERT_EQ(r.exit_code, 0) << r;
  const json m = read_manifest(out);
  EXPECT_EQ(m["compression"]["codec"], "dense");
  for (const json& c : m["transport"]["channels"]) EXPECT_EQ(c["bounces"], 3);
  bool said = false;
  for (const json& l : m["left_out"])
    said = said ||
           (l["where"] == "compress" && contains(l["message"].get<std::string>(), "compression"));
  EXPECT_TRUE(said) << m["left_out"];
  EXPECT_TRUE(fs::exists(out / "T.npy"));
  EXPECT_FALSE(fs::exists(out / "T.dds"));
}

}  // namespace
}  // namespace bounce::itest
