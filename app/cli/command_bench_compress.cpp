// `bounce bench compress`: every BC1 encoder with every ordering on one real
// transport matrix, side by side in one run, against the published pipeline
// (the published pipeline: libsquish cluster fit, the greedy L1 tour in two
// passes, 4% kept) and with our default codec as the last row.
//
// The grid rows are the published pipeline (CodecKind::LargestEntries: its kept split
// and log quantiser) with the encoder and the ordering swapped, so each
// column isolates one of the two; the last row is our whole codec, whose
// quantiser differs too.
//
// Each ordering of the grid is computed once, by the first encoder that needs
// it, and handed to the others as a precomputed permutation (CodecSettings::
// permutation): the paper's tour is O(N^3), minutes at N = 4096 with two
// passes, and it does not depend on the encoder (the codes it orders are the
// same for every encoder of one codec kind and kept fraction).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bench_commands.h"
#include "bounce/compression.h"
#include "bounce/error.h"
#include "commands.h"
#include "console_progress.h"
#include "exact_transport.h"

namespace bounce::cli {

namespace {

constexpr OrderingMethod kAllOrderings[] = {OrderingMethod::None, OrderingMethod::GreedyRowTour,
                                            OrderingMethod::GreedyRowThenColumnTour,
                                            OrderingMethod::SketchTour};

struct CompressBenchOptions {
  BakeOptions bake;  // the scene(s) or bake folder(s), bake settings, --json, --quiet
  std::vector<std::string> encoders = {"weighted", "squish-cluster", "squish-iterative", "stb-hq"};
  std::vector<std::string> orderings = {"none", "paper-1-pass", "paper-2-passes", "ours"};
};

OrderingMethod ordering_from_name(const std::string& name) {
  std::string valid;
  for (const OrderingMethod m : kAllOrderings) {
    if (name == ordering_name(m)) return m;
    valid += (valid.empty() ? "" : ", ") + std::string(ordering_name(m));
  }
  throw Error("--orderings", "unknown ordering '" + name + "' (valid: " + valid + ")");
}

// One compressed variant and what it costs.
struct Row {
  std::string what;  // "<encoder> + <ordering>", or the name of a special row
  std::string encoder, ordering, format, codec;
  double kept_fraction = 0.0;
  double seconds_split = 0.0;
  double seconds_ordering = 0.0;  // of the ordering's one computation
  bool ordering_reused = false;   // computed for an earlier row
  double seconds_encoding = 0.0;
  std::size_t bytes = 0, sparse_bytes = 0, block_bytes = 0, permutation_bytes = 0;
  CompressionErrors errors;
  bool light_weighted = false;
};

// Permutations already computed in this run, per ordering, with the time
// their one computation took.
struct OrderingCache {
  std::map<OrderingMethod, Permutation> permutation;
  std::map<OrderingMethod, double> seconds;
};

class RowRunner {
 public:
  RowRunner(const ExactTransport& exact, Progress& progress, bool verbose, std::size_t steps)
      : exact_(exact), progress_(progress), verbose_(verbose), steps_(steps) {}

  // Compresses with `settings` (its ordering taken from the cache when there,
  // computed and cached otherwise) and measures the errors.
  // With `rebalance`, as bakes compress (compress_for_light: the lights
  // rebalanced when that lowers the worst light's error).
  Row run(const std::string& what, CodecSettings settings, OrderingCache* cache,
          bool rebalance = false) {
    const OrderingMethod ordering = *settings.ordering;
    const bool reuse = cache && cache->permutation.count(ordering) > 0;
    if (reuse) settings.permutation = cache->permutation.at(ordering);
    ++step_;
    if (verbose_)
      std::fprintf(stderr, "[%zu/%zu] %s, kept %g (%s)\n", step_, steps_, what.c_str(),
                   settings.kept_fraction,
                   reuse ? "ordering computed earlier" : "computing the ordering");
    const MeasuredCompression measured =
        rebalance ? compress_for_light(exact_.matrices(), exact_.n, settings, exact_.probe, nullptr,
                                       &progress_)
                  : MeasuredCompression{
                        compress_matrix(exact_.matrices(), exact_.n, settings, &progress_), {}};
    const CompressedMatrix& m = measured.compressed;
    if (cache && !reuse) {
      cache->permutation[ordering] = m.permutation;
      cache->seconds[ordering] = m.seconds_ordering;
    }
    Row r;
    r.what = what;
    r.encoder = m.encoder;
    r.ordering = m.ordering;
    r.codec = m.codec;
    r.format = m.format == DdsFormat::kBc4 ? "BC4" : "BC1";
    r.kept_fraction = m.kept_fraction;
    r.light_weighted = m.light_weighted;
    r.seconds_split = m.seconds_split;
    r.ordering_reused = reuse;
    r.seconds_ordering = reuse ? cache->seconds.at(ordering) : m.seconds_ordering;
    r.seconds_encoding = m.seconds_encoding;
    r.bytes = m.total_bytes();
    r.sparse_bytes = m.sparse_bytes();
    r.block_bytes = m.block_bytes();
    r.permutation_bytes = m.permutation_bytes();
    r.errors = rebalance
                   ? measured.errors
                   : measure_compression(exact_.matrices(), m, exact_.probe, nullptr, &progress_);
    return r;
  }

 private:
  const ExactTransport& exact_;
  Progress& progress_;
  bool verbose_;
  std::size_t steps_;
  std::size_t step_ = 0;
};

struct BenchResult {
  std::vector<Row> grid;        // encoder-major, as listed in the options
  std::optional<Row> paper;     // the reference when it is not in the grid
  std::size_t paper_index = 0;  // the reference's index in `grid` otherwise
  Row ours_largest;             // ours keeping the largest entries, weighing by value only
  Row ours_one_pass;            // ours keeping the largest light-weighted entries, one pass
  Row ours_float32;  // ours light-weighted, kept by a first pass's error, kept entries float32
  Row ours_default;  // the same as bakes store it: float16 kept entries, as many as fit the bytes
  std::vector<Row> extra;  // other block formats (BC4 per channel)
  const Row& reference() const { return paper ? *paper : grid[paper_index]; }
};

double ratio(double a, double b) { return b > 0.0 ? a / b : 0.0; }

void print_row(const Row& r, const Row& ref, const char* mark) {
  const MatrixError& e = r.errors.matrix;
  std::printf(
      "  %-40s %8.2f%s %8.2f %10zu %9.3g %9.3g %9.4g %8.4f %8.4f %8.4f %7.3fx %7.3fx %7.3fx\n",
      (r.what + mark).c_str(), r.seconds_ordering, r.ordering_reused ? "r" : " ",
      r.seconds_encoding, r.bytes, e.mean_abs, e.max_abs, e.sum_abs, e.rel_frobenius,
      r.errors.indirect.rel_rms_mean, r.errors.indirect.rel_rms_max,
      ratio(e.sum_abs, ref.errors.matrix.sum_abs),
      ratio(r.errors.indirect.rel_rms_max, ref.errors.indirect.rel_rms_max),
      ratio(static_cast<double>(r.bytes), static_cast<double>(ref.bytes)));
}

void print_table(const ExactTransport& exact, double kept, const BenchResult& b,
                 const std::vector<Bc1Encoder>& encoders) {
  const Row& ref = b.reference();
  std::printf("\nbench compress: %s, %zu patches, %zu stored channel(s), %s\n", exact.name.c_str(),
              exact.n, exact.channels.size(), exact.source.c_str());
  std::printf("  kept fraction %g (paper row: %g); dense float32 RGB would take %zu bytes\n", kept,
              kPaperKeptFraction, 3 * exact.n * exact.n * sizeof(float));
  std::printf(
      "  rows: the published pipeline (its kept split and log quantiser) with the encoder and "
      "ordering swapped; then our codec keeping the largest entries, and our default codec, "
      "which keeps and weighs entries by the light they carry\n");
  std::printf(
      "  order (s): the ordering's one computation (r = reused from an earlier row); "
      "bytes: kept CSR + blocks + permutation;\n");
  std::printf(
      "  |e| over every entry of every stored channel; rel.Frob = ||T~ - T||_F / "
      "||T||_F; light mean / max = relative RMS error\n");
  std::printf(
      "  of the indirect light, mean and worst over %zu evaluation lights; ratios against the "
      "paper row (marked *)\n",
      ref.errors.indirect.lights);
  std::printf("  %-40s %9s %8s %10s %9s %9s %9s %8s %8s %8s %8s %8s %8s\n", "encoder + ordering",
              "order(s)", "enc(s)", "bytes", "mean|e|", "max|e|", "sum|e|", "rel.Frob", "lightmean",
              "lightmax", "sum/pap", "lmax/pap", "size/pap");
  for (std::size_t k = 0; k < b.grid.size(); ++k) {
    if (k > 0 && b.grid[k].encoder != b.grid[k - 1].encoder) std::printf("\n");
    print_row(b.grid[k], ref, !b.paper && k == b.paper_index ? " *" : "");
  }
  std::printf("\n");
  if (b.paper) print_row(*b.paper, ref, " *");
  print_row(b.ours_largest, ref, "");
  print_row(b.ours_one_pass, ref, "");
  print_row(b.ours_float32, ref, "");
  print_row(b.ours_default, ref, "");
  for (const Row& r : b.extra) print_row(r, ref, "");

  // The codec's two targets, said plainly: sum |error| at most half the
  // paper's at no larger size, and our encoder at least as fast as libsquish's.
  const double sum_ratio = ratio(b.ours_default.errors.matrix.sum_abs, ref.errors.matrix.sum_abs);
  const double size_ratio =
      ratio(static_cast<double>(b.ours_default.bytes), static_cast<double>(ref.bytes));
  const bool met = sum_ratio <= 0.5 && size_ratio <= 1.0;
  std::printf(
      "\n  target 1: ours default sum|e| <= 0.5x paper at no larger size: %.3fx at "
      "%.3fx the size: %s%s\n",
      sum_ratio, size_ratio, met ? "met" : "MISSED",
      exact.n < 4096 ? " (the target is stated for >= 4096 patches)" : "");
  const double light_ratio =
      ratio(b.ours_default.errors.indirect.rel_rms_max, b.ours_largest.errors.indirect.rel_rms_max);
  std::printf(
      "  light-weighted against largest kept, same size (%.3fx): worst-light error %.4f vs "
      "%.4f (%.3fx); paper %.4f\n",
      ratio(static_cast<double>(b.ours_default.bytes), static_cast<double>(b.ours_largest.bytes)),
      b.ours_default.errors.indirect.rel_rms_max, b.ours_largest.errors.indirect.rel_rms_max,
      light_ratio, ref.errors.indirect.rel_rms_max);
  // Encoding speed, summed over the orderings so one noisy run weighs less.
  auto encode_total = [&](Bc1Encoder enc) {
    double s = 0.0;
    for (const Row& r : b.grid)
      if (r.encoder == bc1_encoder_name(enc)) s += r.seconds_encoding;
    return s;
  };
  const bool both =
      std::find(encoders.begin(), encoders.end(), Bc1Encoder::kWeighted) != encoders.end() &&
      std::find(encoders.begin(), encoders.end(), Bc1Encoder::kSquishClusterFit) != encoders.end();
  if (both) {
    const double ours = encode_total(Bc1Encoder::kWeighted),
                 squish = encode_total(Bc1Encoder::kSquishClusterFit);
    std::printf(
        "  target 2: our encoder at least as fast as libsquish cluster fit: %.2f s vs "
        "%.2f s encoding, summed over the orderings (%.2fx the time): %s\n",
        ours, squish, ratio(ours, squish), ours <= squish ? "met" : "MISSED");
  }
}

nlohmann::json row_json(const Row& r, const Row& ref) {
  const MatrixError& e = r.errors.matrix;
  return {{"what", r.what},
          {"codec", r.codec},
          {"encoder", r.encoder},
          {"ordering", r.ordering},
          {"format", r.format},
          {"kept_fraction", r.kept_fraction},
          {"seconds_split", r.seconds_split},
          {"seconds_ordering", r.seconds_ordering},
          {"ordering_reused", r.ordering_reused},
          {"seconds_encoding", r.seconds_encoding},
          {"bytes", r.bytes},
          {"sparse_bytes", r.sparse_bytes},
          {"block_bytes", r.block_bytes},
          {"permutation_bytes", r.permutation_bytes},
          {"mean_abs", e.mean_abs},
          {"max_abs", e.max_abs},
          {"sum_abs", e.sum_abs},
          {"rel_frobenius", e.rel_frobenius},
          {"indirect_lights", r.errors.indirect.lights},
          {"indirect_rel_rms_mean", r.errors.indirect.rel_rms_mean},
          {"indirect_rel_rms_max", r.errors.indirect.rel_rms_max},
          {"light_weighted", r.light_weighted},
          {"indirect_rel_rms_max_vs_paper",
           ratio(r.errors.indirect.rel_rms_max, ref.errors.indirect.rel_rms_max)},
          {"sum_abs_vs_paper", ratio(e.sum_abs, ref.errors.matrix.sum_abs)},
          {"bytes_vs_paper", ratio(static_cast<double>(r.bytes), static_cast<double>(ref.bytes))}};
}

nlohmann::json result_json(const ExactTransport& exact, double kept, const BenchResult& b) {
  const Row& ref = b.reference();
  nlohmann::json grid = nlohmann::json::array();
  for (const Row& r : b.grid) grid.push_back(row_json(r, ref));
  nlohmann::json extra = nlohmann::json::array();
  for (const Row& r : b.extra) extra.push_back(row_json(r, ref));
  return {{"scene", exact.name},
          {"source", exact.source},
          {"patches", exact.n},
          {"stored_channels", exact.channels.size()},
          {"bake_seconds", exact.bake_seconds},
          {"kept_fraction", kept},
          {"dense_rgb_bytes", 3 * exact.n * exact.n * sizeof(float)},
          {"grid", grid},
          {"paper", row_json(ref, ref)},
          {"ours_largest_kept", row_json(b.ours_largest, ref)},
          {"ours_light_weighted_one_pass", row_json(b.ours_one_pass, ref)},
          {"ours_light_weighted_float32_kept", row_json(b.ours_float32, ref)},
          {"ours_default", row_json(b.ours_default, ref)},
          {"other_formats", extra}};
}

BenchResult run_one(const ExactTransport& exact, double kept,
                    const std::vector<Bc1Encoder>& encoders,
                    const std::vector<OrderingMethod>& orderings, Progress& progress,
                    bool verbose) {
  const auto has_encoder = [&](Bc1Encoder e) {
    return std::find(encoders.begin(), encoders.end(), e) != encoders.end();
  };
  const auto has_ordering = [&](OrderingMethod o) {
    return std::find(orderings.begin(), orderings.end(), o) != orderings.end();
  };
  const bool paper_in_grid = kept == kPaperKeptFraction &&
                             has_encoder(Bc1Encoder::kSquishClusterFit) &&
                             has_ordering(OrderingMethod::GreedyRowThenColumnTour);
  const std::size_t steps = encoders.size() * orderings.size() + (paper_in_grid ? 4 : 5) +
                            (exact.channels.size() > 1 ? 3 : 0);
  RowRunner runner(exact, progress, verbose, steps);
  OrderingCache cache;

  // Ordering-major, so each ordering is computed by the first encoder and
  // reused by the rest; the table lists the rows encoder-major.
  BenchResult b;
  b.grid.resize(encoders.size() * orderings.size());
  for (std::size_t o = 0; o < orderings.size(); ++o)
    for (std::size_t e = 0; e < encoders.size(); ++e) {
      CodecSettings s;
      s.kind = CodecKind::LargestEntries;  // the published quantiser; encoder and ordering swapped
      s.kept_fraction = kept;
      s.bc1_encoder = encoders[e];
      s.ordering = orderings[o];
      const std::size_t index = e * orderings.size() + o;
      b.grid[index] = runner.run(
          std::string(bc1_encoder_name(encoders[e])) + " + " + ordering_name(orderings[o]), s,
          &cache);
      if (paper_in_grid && encoders[e] == Bc1Encoder::kSquishClusterFit &&
          orderings[o] == OrderingMethod::GreedyRowThenColumnTour)
        b.paper_index = index;
    }

  if (!paper_in_grid) {
    CodecSettings s;
    s.kind = CodecKind::LargestEntries;
    s.kept_fraction = kPaperKeptFraction;
    s.bc1_encoder = Bc1Encoder::kSquishClusterFit;
    s.ordering = OrderingMethod::GreedyRowThenColumnTour;
    // The grid's orderings were computed on codes of another kept fraction.
    b.paper = runner.run("paper: squish-cluster + paper-2-passes", s,
                         kept == kPaperKeptFraction ? &cache : nullptr);
  }

  // Our codec at the same kept fraction and the same bytes (kept entries in
  // float32, as the paper stores them), three times: keeping the largest
  // entries (as it did before it knew the light), keeping and weighing entries
  // by the light their columns carry over the evaluation lights (one pass),
  // and with a second pass keeping what the first decoded worst. Its
  // quantiser gives other codes than the paper's, and the holes differ
  // between the two, so each ordering is computed anew.
  CodecSettings s;
  s.kind = CodecKind::LightWeighted;
  s.kept_fraction = kept;
  s.ordering = OrderingMethod::SketchTour;
  s.kept_storage = KeptStorage::kFloat32;
  b.ours_largest = runner.run("ours, largest entries kept", s, nullptr);
  const EntryImportance importance =
      light_importance(exact.matrices(), exact.n, exact.probe.first_hit, exact.probe.channel_of_rgb,
                       exact.probe.area);
  CodecSettings weighted = s;
  weighted.importance = &importance;
  weighted.kept_passes = 1;
  b.ours_one_pass = runner.run("ours, light-weighted, one pass", weighted, nullptr);
  weighted.kept_passes = CodecSettings{}.kept_passes;
  b.ours_float32 = runner.run("ours, light-weighted, float32 kept", weighted, nullptr, true);
  // As bakes store it: kept entries in half precision with 16-bit columns,
  // as many more as fit in the bytes the float32 entries took.
  weighted.kept_storage = KeptStorage::kFloat16;
  weighted.kept_fraction =
      std::min(1.0, kept * static_cast<double>(kept_entry_bytes(KeptStorage::kFloat32, exact.n)) /
                        static_cast<double>(kept_entry_bytes(KeptStorage::kFloat16, exact.n)));
  b.ours_default =
      runner.run("ours, light-weighted, float16 kept (default codec)", weighted, nullptr, true);

  // The other block format that might win: BC4 per channel, 8 bytes
  // per block and channel where BC1 spends 8 on all three. Once at the same
  // kept fraction (3x the block bytes), once at the same total size: the two
  // extra images (2 x padded^2 / 2 bytes) paid for by keeping padded^2 / 8
  // fewer entries (8 bytes each in CSR) over the three channels.
  if (exact.channels.size() > 1) {
    CodecSettings bc4 = s;
    bc4.bc4_per_channel = true;
    b.extra.push_back(runner.run("ours, BC4 per channel (same kept)", bc4, nullptr));
    const double padded = static_cast<double>((exact.n + 3) / 4 * 4);
    const double fewer = padded * padded / 8.0 /
                         (static_cast<double>(exact.channels.size()) *
                          static_cast<double>(exact.n) * static_cast<double>(exact.n));
    bc4.kept_fraction = std::max(0.0, kept - fewer);
    b.extra.push_back(runner.run("ours, BC4 per channel (same size)", bc4, nullptr));
    bc4.importance = &importance;
    b.extra.push_back(
        runner.run("ours, BC4 per channel, light-weighted (same size)", bc4, nullptr));
  }
  return b;
}

void run(const CompressBenchOptions& opt) {
  const BakeOptions& bo = opt.bake;
  if (bo.given("codec") && bo.texts.at("codec") != "auto")
    throw Error("--codec", "does not apply to bench compress, which compares every codec");
  if (bo.given("error_budget"))
    throw Error("--error-budget",
                "does not apply to bench compress, which compares codecs at one --kept-fraction");
  if (bo.given("size_limit"))
    throw Error("--size-limit",
                "does not apply to bench compress, which compares codecs at one --kept-fraction");
  const double kept = bo.settings().kept_fraction.value_or(kPaperKeptFraction);
  if (!(kept > 0.0 && kept < 1.0))
    throw Error("--kept-fraction",
                "must be between 0 and 1 (exclusive), got " + std::to_string(kept));
  std::vector<Bc1Encoder> encoders;
  for (const std::string& name : opt.encoders) {
    try {
      encoders.push_back(bc1_encoder_from_name(name.c_str()));
    } catch (const Error& e) {
      throw Error("--encoders", e.what());
    }
  }
  std::vector<OrderingMethod> orderings;
  for (const std::string& name : opt.orderings) orderings.push_back(ordering_from_name(name));
  if (encoders.empty() || orderings.empty())
    throw Error("--encoders/--orderings", "need at least one encoder and one ordering");

  ConsoleProgress console(bo.quiet || bo.json);
  const bool verbose = !bo.quiet && !bo.json;
  nlohmann::json all = nlohmann::json::array();
  for (const std::string& path : expand_globs(bo.scenes)) {
    ExactTransport exact;
    if (is_bake_folder(path)) {
      if (verbose)
        std::fprintf(stderr, "reading the exact matrix from the bake folder %s\n", path.c_str());
      exact = read_bake_folder(path);
    } else {
      if (verbose)
        std::fprintf(stderr, "baking %s with the dense codec to get the exact matrix\n",
                     path.c_str());
      exact = bake_exact_transport(path, bo.settings(), console.progress());
    }
    const BenchResult b = run_one(exact, kept, encoders, orderings, console.progress(), verbose);
    if (bo.json) {
      all.push_back(result_json(exact, kept, b));
    } else {
      print_table(exact, kept, b, encoders);
      std::fflush(stdout);
    }
  }
  if (bo.json) std::cout << all.dump(2) << '\n';
}

}  // namespace

void register_bench_compress(CLI::App& bench) {
  auto opt = std::make_shared<CompressBenchOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "compress",
      "Every BC1 encoder x every ordering on one transport matrix, against the paper's pipeline");
  cmd->footer(
      "SCENE is baked first with the dense codec (the bake options above apply; nothing is "
      "written); a BAKE folder from `bounce bake` is read as it is and needs T.npy (bake with "
      "--dump-matrices). Then one table, one row per encoder and ordering: ordering and encoding "
      "seconds, total bytes (kept CSR + blocks + permutation), mean/max/sum |error|, relative "
      "Frobenius error, indirect-light error (relative RMS, mean and worst over the evaluation "
      "lights), and sum |error|, worst light error and size relative to the paper row (libsquish "
      "cluster fit, paper's "
      "2-pass ordering, 4% kept). Every row but the last is the published pipeline (its kept "
      "split and log quantiser) with the encoder and ordering swapped; the last rows are our "
      "codec at the same kept fraction keeping the largest entries, and as bakes use it, "
      "keeping and weighing entries by the light they carry. "
      "Each ordering is computed once and shared by the encoders. Takes minutes: the paper's "
      "ordering is O(N^3).\n\nExample:\n  bounce bench compress resources/scenes/cornell-bunny "
      "--patches-total 4096");
  opt->bake.add_to(*cmd, false);
  // The bake options fit, but three mean something else here.
  cmd->get_option("scenes")->description(
      "Scene(s) to bake (scene folder, scene.json or mesh file), or bake folder(s) holding "
      "T.npy, lights_first_hit.npy, patches.npy and manifest.json");
  CLI::Option* kept_fraction = opt->bake.option("kept_fraction");
  CLI::Option* error_budget = opt->bake.option("error_budget");
  CLI::Option* size_limit = opt->bake.option("size_limit");
  kept_fraction->description(
      "Share of each channel's largest entries kept exactly, for every row of the table "
      "(default 0.04, the paper's; the paper row always keeps 0.04)");
  cmd->get_option("--codec")->group("");  // hidden: the bench compares every codec
  error_budget->group("");
  size_limit->group("");
  kept_fraction->remove_excludes(error_budget);
  kept_fraction->remove_excludes(size_limit);
  size_limit->remove_excludes(kept_fraction);
  error_budget->remove_excludes(kept_fraction);
  cmd->add_option("--encoders", opt->encoders,
                  "BC1 encoders to compare, comma-separated: weighted (ours), squish-cluster "
                  "(the paper's), squish-cluster-masked, squish-iterative, squish-range, stb-hq")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--orderings", opt->orderings,
                  "Row/column orderings to compare, comma-separated: none, paper-1-pass, "
                  "paper-2-passes (the paper's), ours")
      ->delimiter(',')
      ->capture_default_str();
  cmd->callback([opt]() { run(*opt); });
}

}  // namespace bounce::cli
