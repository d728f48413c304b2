// `mpirun -np R bounce bake` against the single-process bake of the same
// scene and settings: form factors bit for bit, the transport
// matrix within a tolerance derived from the floating-point error of the two
// summation orders, the manifest's checks equal; the compression (block rows
// encoded by every rank) byte for byte; and errors reported once by rank 0
// with nothing written.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

#include "cli_harness.h"

namespace bounce::itest {
namespace {

const std::string kBounce = BOUNCE_BIN;
const std::string kMpiexec = BOUNCE_MPIEXEC;

// A small Cornell box: about 200 patches, a few seconds per bake.
const std::vector<std::string> kSettings = {"--voxel", "4",     "--dump-matrices",
                                            "--codec", "dense", "--quiet"};

std::vector<std::string> single(std::vector<std::string> args) {
  args.insert(args.begin(), kBounce);
  return args;
}

std::vector<std::string> distributed(int ranks, std::vector<std::string> args) {
  std::vector<std::string> all = {kMpiexec, "--allow-run-as-root", "--oversubscribe",
                                  "-np",    std::to_string(ranks), kBounce};
  all.insert(all.end(), args.begin(), args.end());
  return all;
}

std::vector<std::string> bake(const fs::path& out, const std::string& bounces) {
  std::vector<std::string> args = {"bake",       scene("cornell-box"), "--out",
                                   out.string(), "--bounces",          bounces};
  args.insert(args.end(), kSettings.begin(), kSettings.end());
  return args;
}

RunResult run_in(const TempDir& dir, const std::vector<std::string>& args) {
  RunOptions o;
  o.cwd = dir.path();
  o.timeout = std::chrono::seconds(120);
  // One OpenMP/OpenBLAS thread per rank: R ranks share this machine's cores.
  o.env["OMP_NUM_THREADS"] = "1";
  o.env["OPENBLAS_NUM_THREADS"] = "1";
  return run(args, o);
}

// The single-process bakes the tests compare with, made once per process
// and only those a test asks for (ctest runs each test in its own process).
class DistributedBake : public ::testing::Test {
 protected:
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static fs::path reference(const std::string& bounces) {
    if (!dir_) dir_ = new TempDir();
    const fs::path out = dir_->path() / ("single-" + bounces);
    if (!fs::exists(out)) {
      const RunResult r = run_in(*dir_, single(bake(out, bounces)));
      EXPECT_EQ(r.exit_code, 0) << r;
    }
    return out;
  }
  // The single-process bake of compressed_bake with `codec`.
  static fs::path compressed_reference(const std::string& codec);
  static TempDir* dir_;
};
TempDir* DistributedBake::dir_ = nullptr;

void expect_same_bytes(const fs::path& a, const fs::path& b) {
  const std::string x = read_text(a), y = read_text(b);
  ASSERT_FALSE(x.empty()) << a;
  EXPECT_TRUE(x == y) << a.filename() << " differs between " << a.parent_path() << " and "
                      << b.parent_path();
}

// What a distributed bake must share with the single-process one exactly:
// geometry, form factors (each entry computed by one rank, identically) and
// everything derived from them alone.
void expect_same_up_to_transport(const fs::path& one, const fs::path& many, int ranks) {
  for (const char* file : {"patches.npy", "samples.npy", "voxels.npy", "F.npy"})
    expect_same_bytes(one / file, many / file);
  const json a = read_manifest(one), b = read_manifest(many);
  EXPECT_EQ(a["checks"], b["checks"]);
  EXPECT_EQ(a["counts"], b["counts"]);
  ASSERT_EQ(a["transport"]["channels"].size(), b["transport"]["channels"].size());
  for (std::size_t c = 0; c < a["transport"]["channels"].size(); ++c) {
    const json& x = a["transport"]["channels"][c];
    const json& y = b["transport"]["channels"][c];
    EXPECT_EQ(x["rgb"], y["rgb"]);
    EXPECT_EQ(x["bounces"], y["bounces"]);
    EXPECT_EQ(x["precision"], y["precision"]);
    // K = infinity: Cholesky here, LU on ScaLAPACK, and the spectral radius
    // read off each T, equal to the solve's rounding. A series: both from F.
    const std::string method = x["method"];
    if (method.starts_with("Cholesky") || method.starts_with("LU")) {
      EXPECT_NEAR(x["spectral_radius"].get<double>(), y["spectral_radius"].get<double>(),
                  1e-5 * x["spectral_radius"].get<double>());
    } else {
      EXPECT_EQ(x["method"], y["method"]);
      EXPECT_EQ(x["spectral_radius"], y["spectral_radius"]);  // computed from F alone
    }
  }
  const std::string decisions = b["transport"]["decisions"].dump();
  EXPECT_TRUE(contains(decisions, "ScaLAPACK")) << decisions;
  EXPECT_TRUE(contains(decisions, "on " + std::to_string(ranks) + " MPI ranks")) << decisions;
}

struct Difference {
  double max_relative = 0.0;  // max |a - b| / max(|a|, |b|) over the entries
  double frobenius = 0.0;     // ||a - b||_F / ||a||_F
};

Difference difference(const fs::path& a_path, const fs::path& b_path) {
  const auto a = read_npy_f32(a_path), b = read_npy_f32(b_path);
  EXPECT_EQ(a.shape, b.shape);
  Difference d;
  double diff2 = 0.0, norm2 = 0.0;
  for (std::size_t i = 0; i < std::min(a.data.size(), b.data.size()); ++i) {
    const double x = a.data[i], y = b.data[i];
    EXPECT_TRUE(std::isfinite(y));
    const double scale = std::max(std::abs(x), std::abs(y));
    if (scale > 0.0) d.max_relative = std::max(d.max_relative, std::abs(x - y) / scale);
    diff2 += (x - y) * (x - y);
    norm2 += x * x;
  }
  d.frobenius = norm2 > 0.0 ? std::sqrt(diff2 / norm2) : 0.0;
  return d;
}

constexpr double kUnitRoundoff = FLT_EPSILON / 2.0;

TEST_F(DistributedBake, TwoRanksEqualOneProcessWithFourBounces) {
  TempDir work;
  const fs::path out = work / "two";
  const RunResult r = run_in(work, distributed(2, bake(out, "4")));
  ASSERT_EQ(r.exit_code, 0) << r;
  expect_same_up_to_transport(reference("4"), out, 2);
  // T = M + M^2 + M^3 + M^4 by three float32 products of non-negative
  // matrices. Each computed product entry is within gamma_n = n u / (1 - n u)
  // of exact, relative, in any summation order, and each sum of non-negative
  // terms within u; through K - 1 = 3 nested products and sums each bake is
  // within (K - 1)(gamma_n + u) of the exact T entry by entry, so the two
  // differ by at most twice that.
  const json m = read_manifest(out);
  const double n = m["transport"]["patches"].get<double>();
  const double gamma = n * kUnitRoundoff / (1.0 - n * kUnitRoundoff);
  const double tolerance = 2.0 * 3.0 * (gamma + kUnitRoundoff);
  const Difference d = difference(reference("4") / "T.npy", out / "T.npy");
  EXPECT_LE(d.max_relative, tolerance) << "n = " << n;
  std::printf("4 bounces, 2 ranks: max relative difference %.3g (bound %.3g), Frobenius %.3g\n",
              d.max_relative, tolerance, d.frobenius);
}

TEST_F(DistributedBake, FourRanksEqualOneProcessWithInfiniteBounces) {
  TempDir work;
  const fs::path out = work / "four";
  const RunResult r = run_in(work, distributed(4, bake(out, "inf")));
  ASSERT_EQ(r.exit_code, 0) << r;
  expect_same_up_to_transport(reference("inf"), out, 4);
  // T solves (I - M) T = M by LU with partial pivoting. I - M^T is column
  // diagonally dominant (row sums of M = albedo x form-factor row sums < 1),
  // so partial pivoting does not pivot and the growth factor is at most 2;
  // the backward error is then within 2 gamma_3n |I - M| and the forward
  // error within kappa times that (Higham, ch. 9). Each bake is within
  // kappa 2 gamma_3n of the exact T in norm; the two differ by twice that.
  const json m = read_manifest(out);
  const double n = m["transport"]["patches"].get<double>();
  const double gamma3n = 3.0 * n * kUnitRoundoff / (1.0 - 3.0 * n * kUnitRoundoff);
  for (const json& channel : m["transport"]["channels"])
    ASSERT_EQ(channel["precision"], "float32") << "the bound below is for float32";
  // kappa: the larger estimate of the two bakes (LAPACK's and ScaLAPACK's
  // estimators are both lower bounds of the true condition number).
  double kappa = 0.0;
  const json single_manifest = read_manifest(reference("inf"));
  for (const json* manifest : {&single_manifest, &m})
    for (const json& channel : (*manifest)["transport"]["channels"])
      kappa = std::max(kappa, channel["condition_number"].get<double>());
  ASSERT_GT(kappa, 0.0);
  // The distributed bake computes kappa_inf(I - M) exactly ((I - M)^-1 =
  // I + T); a single process solving by LU estimates the same number with
  // LAPACK's ?gecon, a lower bound. By Cholesky it estimates the condition of
  // another matrix (the symmetrised S, 1-norm), which bounds nothing here.
  const json& many = m["transport"]["channels"];
  const json& one = single_manifest["transport"]["channels"];
  ASSERT_EQ(many.size(), one.size());
  for (std::size_t c = 0; c < many.size(); ++c)
    if (one[c]["method"].get<std::string>().rfind("LU", 0) == 0) {
      EXPECT_GE(many[c]["condition_number"].get<double>(),
                (1.0 - 1e-3) * one[c]["condition_number"].get<double>());
    }
  const double tolerance = 2.0 * kappa * 2.0 * gamma3n;
  const Difference d = difference(reference("inf") / "T.npy", out / "T.npy");
  EXPECT_LE(d.frobenius, tolerance) << "n = " << n << ", kappa = " << kappa;
  std::printf("K = inf, 4 ranks: relative Frobenius difference %.3g (bound %.3g), max entry %.3g\n",
              d.frobenius, tolerance, d.max_relative);
}

// A bake whose compression the ranks share: K = 1, so T = M = diag(albedo) F
// is computed without any product and is the same bytes in every bake (F is,
// and no summation order differs); every file of the compressed bake must
// then be too. --dump-matrices adds F.npy and T.npy, pictures are written.
std::vector<std::string> compressed_bake(const fs::path& out, const std::string& codec) {
  return {"bake",
          scene("cornell-box"),
          "--out",
          out.string(),
          "--voxel",
          "4",
          "--bounces",
          "1",
          "--codec",
          codec,
          "--dump-matrices",
          "--quiet"};
}

fs::path DistributedBake::compressed_reference(const std::string& codec) {
  if (!dir_) dir_ = new TempDir();
  const fs::path out = dir_->path() / ("single-" + codec);
  if (!fs::exists(out)) {
    const RunResult r = run_in(*dir_, single(compressed_bake(out, codec)));
    EXPECT_EQ(r.exit_code, 0) << r;
  }
  return out;
}

// Every file of the two bake folders byte for byte (the kept entries, the
// permutation, T.dds's blocks, the pictures ...), and the manifest's
// compression record equal apart from times and decisions; the ranks did
// share the block encoding, and sent their compress stage's peak memory.
void expect_same_compressed_bake(const fs::path& one, const fs::path& many, int ranks) {
  const std::vector<std::string> files = entries(one);
  ASSERT_EQ(files, entries(many));
  for (const char* needed : {"T.dds", "permutation.npy", "T.npy", "F.npy"})
    EXPECT_NE(std::find(files.begin(), files.end(), needed), files.end()) << needed;
  for (const std::string& f : files)
    if (f != "manifest.json") expect_same_bytes(one / f, many / f);
  const json a = read_manifest(one), b = read_manifest(many);
  for (const char* key : {"codec", "encoder", "error_budget", "errors", "format", "kept_fraction",
                          "kept_fraction_trials", "ordering", "padded_size", "quantizers", "sizes",
                          "stored_channels"})
    EXPECT_EQ(a["compression"][key], b["compression"][key]) << key;
  const std::string decisions = b["compression"]["decisions"].dump();
  EXPECT_TRUE(contains(decisions, "block encoding")) << decisions;
  EXPECT_TRUE(contains(decisions, "on " + std::to_string(ranks) + " MPI ranks")) << decisions;
  bool compress_stage = false;
  for (const json& s : b["stages"])
    if (s["name"] == "compress") {
      compress_stage = true;
      EXPECT_GT(s.value("peak_rss_bytes_other_ranks", 0.0), 0.0) << s.dump();
    }
  EXPECT_TRUE(compress_stage);
}

// The compressed bake with `codec` on `ranks` ranks, in `work`, compared
// with the single process's; returns its folder.
fs::path bake_on_ranks_like_one_process(const TempDir& work, int ranks, const std::string& codec,
                                        const fs::path& reference) {
  const fs::path out = work / ("ranks-" + std::to_string(ranks));
  const RunResult r = run_in(work, distributed(ranks, compressed_bake(out, codec)));
  EXPECT_EQ(r.exit_code, 0) << r;
  if (r.exit_code == 0) expect_same_compressed_bake(reference, out, ranks);
  return out;
}

TEST_F(DistributedBake, TwoRanksCompressLikeOneProcessWithOurCodec) {
  TempDir work;
  const fs::path out =
      bake_on_ranks_like_one_process(work, 2, "ours", compressed_reference("ours"));
  // The error budget tried several kept fractions, each one encoding shared
  // by the ranks.
  EXPECT_GE(read_manifest(out)["compression"]["kept_fraction_trials"].size(), 2u);
}

TEST_F(DistributedBake, FourRanksCompressLikeOneProcessWithOurCodec) {
  TempDir work;
  bake_on_ranks_like_one_process(work, 4, "ours", compressed_reference("ours"));
}

TEST_F(DistributedBake, TwoRanksCompressLikeOneProcessWithPaperCodec) {
  TempDir work;
  bake_on_ranks_like_one_process(work, 2, "paper", compressed_reference("paper"));
}

TEST_F(DistributedBake, FourRanksCompressLikeOneProcessWithPaperCodec) {
  TempDir work;
  bake_on_ranks_like_one_process(work, 4, "paper", compressed_reference("paper"));
}

// A stage's peak RSS in a manifest: this process's (rank 0's), or with
// `other_ranks` the highest of the other ranks'.
double stage_peak(const json& manifest, const std::string& stage, bool other_ranks) {
  for (const json& s : manifest["stages"])
    if (s["name"] == stage) {
      const char* key = other_ranks ? "peak_rss_bytes_other_ranks" : "peak_rss_bytes";
      EXPECT_TRUE(s.contains(key)) << stage << " has no " << key;
      return s.contains(key) ? s[key].get<double>() : 0.0;
    }
  ADD_FAILURE() << "no stage " << stage;
  return 0.0;
}

TEST(DistributedBakeMemory, OtherRankHoldsItsShareOfTheTransportNotWholeMatrices) {
  TempDir work;
  const std::vector<std::string> settings = {"--patches-total", "800",   "--bounces", "4",
                                             "--codec",         "dense", "--quiet"};
  auto args = [&](const fs::path& out) {
    std::vector<std::string> a = {"bake", scene("cornell-box"), "--out", out.string()};
    a.insert(a.end(), settings.begin(), settings.end());
    return a;
  };
  const RunResult one = run_in(work, single(args(work / "one")));
  ASSERT_EQ(one.exit_code, 0) << one;
  const RunResult two = run_in(work, distributed(2, args(work / "two")));
  ASSERT_EQ(two.exit_code, 0) << two;
  const json a = read_manifest(work / "one"), b = read_manifest(work / "two");
  const double n = b["transport"]["patches"].get<double>();
  const double matrix = 4.0 * n * n;  // one n x n float32 matrix, bytes
  // Each process's growth over its own "patches" stage, the last before any
  // n x n matrix: up to there every process runs the same code on the same
  // data, so the baseline carries what differs between processes (MPI's
  // libraries and buffers, the progress display) and what the heap kept from
  // the clustering, alike.
  const double single_growth = stage_peak(a, "transport", false) - stage_peak(a, "patches", false);
  const double other_growth = stage_peak(b, "transport", true) - stage_peak(b, "patches", true);
  // The single process's transport holds F, M and at least one T (3 matrices)
  // at once. The other rank of two holds no F and no whole operand: its
  // shares of A, B and C of a product, 3 x matrix / 2. The gap is at least
  // 1.5 matrices; asserting one leaves half a matrix for the noise of RSS.
  // (Before operands were sent by share, that rank held F and whole copies of
  // A and B besides the shares: 4.5 matrices, more than the single process.)
  EXPECT_LT(other_growth + matrix, single_growth)
      << "n = " << n << ": other rank grew " << other_growth / 1e6 << " MB, single process "
      << single_growth / 1e6 << " MB, one matrix " << matrix / 1e6 << " MB";
  // Rank 0's own peak and the highest over all ranks are both reported.
  for (const json& s : b["stages"]) {
    if (!s.contains("peak_rss_bytes_other_ranks")) continue;
    EXPECT_EQ(
        s["peak_rss_bytes_all_ranks"].get<double>(),
        std::max(s["peak_rss_bytes"].get<double>(), s["peak_rss_bytes_other_ranks"].get<double>()));
  }
  std::printf(
      "n = %.0f: transport growth over the patches stage, other rank %.1f MB, single "
      "process %.1f MB (one matrix %.1f MB)\n",
      n, other_growth / 1e6, single_growth / 1e6, matrix / 1e6);
}

TEST(DistributedBakeErrors, BadSceneIsOneErrorOnRankZeroAndNothingWritten) {
  TempDir work;
  const fs::path out = work / "bad";
  const RunResult r = run_in(
      work, distributed(2, {"bake", (work / "missing.obj").string(), "--out", out.string()}));
  EXPECT_EQ(r.exit_code, 1) << r;
  EXPECT_EQ(lines_starting_with(r.err, "bounce: error:").size(), 1u) << r;
  EXPECT_TRUE(contains(r.err, "missing.obj")) << r;
  EXPECT_FALSE(fs::exists(out));
}

TEST(DistributedBakeErrors, RankFailingInCompressionIsOneErrorOnRankZeroAndNothingWritten) {
  TempDir work;
  const fs::path out = work / "failed";
  RunOptions o;
  o.cwd = work.path();
  o.timeout = std::chrono::seconds(120);
  o.env["OMP_NUM_THREADS"] = "1";
  o.env["OPENBLAS_NUM_THREADS"] = "1";
  // Rank 1 fails its share of the block encoding (mpi_compression.cpp).
  o.env["BOUNCE_TEST_FAIL_BLOCK_ENCODING_ON_RANK"] = "1";
  const RunResult r = run(distributed(2, compressed_bake(out, "ours")), o);
  EXPECT_NE(r.exit_code, 0) << r;
  const auto errors = lines_starting_with(r.err, "bounce: error:");
  ASSERT_EQ(errors.size(), 1u) << r;
  EXPECT_TRUE(contains(errors[0], "block encoding failed on rank 1 of 2")) << r;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(hidden_leftovers(out).empty());
}

TEST(DistributedBakeErrors, BatchIsRefusedWithNothingWritten) {
  TempDir work;
  const fs::path out = work / "batch";
  const RunResult r = run_in(work, distributed(2, {"bake", scene("cornell-box"), scene("furnace"),
                                                   "--out", out.string()}));
  EXPECT_EQ(r.exit_code, 1) << r;
  EXPECT_TRUE(contains(r.err, "takes one scene")) << r;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace bounce::itest
