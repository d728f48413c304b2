#include "bake/matrix_storage.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "compress/entry_importance.h"
#include "compress/light_rebalance.h"
#include "transport/text_format.h"

namespace bounce {

namespace {

using Clock = std::chrono::steady_clock;

using Trial = MeasuredCompression;

// The kept-fraction search's state: one ordering and one sample of rows for
// every sampled trial, each rung's light error on the sample measured once;
// each whole compression made once. The sample is compressed with the
// importance as given. A whole compression is first made as given; the
// lights rebalanced by its own per-light errors (rebalance_for_light) are
// tried only where that can change the outcome: on a rung that misses the
// budget, and on the rung kept. A sample does not see the few rows where one
// light's error concentrates, so weights taken from it can make that light
// worse.
class KeptFractionSearch {
 public:
  // `codec`: with its permutation, sample of block rows and kept storage.
  KeptFractionSearch(const std::vector<const float*>& exact, std::size_t n, CodecSettings codec,
                     const IndirectLightProbe& probe, double budget, MatrixStorage& s,
                     Progress* progress, CompressionExecutor* executor)
      : exact_(exact),
        n_(n),
        codec_(std::move(codec)),
        probe_(probe),
        budget_(budget),
        s_(s),
        progress_(progress),
        executor_(executor) {}

  // The light error (what the budget bounds) of `rung` on the sample.
  double sampled_error(int rung) {
    if (const auto it = sampled_.find(rung); it != sampled_.end()) return it->second;
    CodecSettings codec = codec_;
    codec.kept_fraction = kKeptFractionLadder[rung];
    const CompressedMatrix m = compress_matrix(exact_, n_, codec, progress_);
    const CompressionErrors e = measure_compression(exact_, m, probe_, nullptr, progress_);
    record(codec.kept_fraction, e,
           predicted_total_bytes(n_, static_cast<int>(exact_.size()), codec.kept_fraction,
                                 *codec_.kept_storage),
           m.rows().size());
    return sampled_[rung] = budgeted_light_error(e.indirect);
  }
  std::size_t sampled_count() const { return sampled_.size(); }

  // The light error of the whole matrix compressed at `rung`, as far as it
  // has been improved.
  double whole_error(int rung) { return budgeted_light_error(whole_light_error(rung)); }

  // Whether the whole matrix at `rung` meets the budget, with the lights
  // rebalanced when it does not as given.
  bool meets(int rung) {
    if (whole_error(rung) <= budget_) return true;
    finish(rung);
    return whole_error(rung) <= budget_;
  }

  // The whole matrix's light error at `rung` per light: its mean is about as
  // low as rebalancing the lights can bring the worst.
  const IndirectLightError& whole_light_error(int rung) {
    return whole(rung).trial.errors.indirect;
  }

  // Tries the lights rebalanced at `rung` (once).
  void finish(int rung) {
    Whole& w = whole(rung);
    const bool rebalanced_before = w.trial.compressed.lights_rebalanced;
    w.trial = rebalance_for_light(std::move(w.trial), exact_, n_, whole_codec(rung), probe_, &w.map,
                                  progress_, executor_);
    if (w.trial.compressed.lights_rebalanced && !rebalanced_before)
      record(kKeptFractionLadder[rung], w.trial.errors, w.trial.compressed.total_bytes(), n_);
  }

  // The whole compression at `rung` with its rebalancing tried, for keeping
  // (`error_map`: the error picture's |T~ - T| sums).
  Trial take(int rung, std::vector<float>& error_map) {
    finish(rung);
    Whole& w = whole(rung);
    error_map.swap(w.map);
    return std::move(w.trial);
  }

 private:
  struct Whole {
    Trial trial;
    std::vector<float> map;
  };

  // Its own ordering, as a bake given this kept fraction computes it: the
  // stored matrix is the one that bake (or the studio's re-compression at the
  // bake's kept fraction) makes, byte for byte.
  CodecSettings whole_codec(int rung) const {
    CodecSettings codec = codec_;
    codec.block_rows.clear();
    codec.permutation.reset();
    codec.kept_fraction = kKeptFractionLadder[rung];
    return codec;
  }

  Whole& whole(int rung) {
    if (const auto it = whole_.find(rung); it != whole_.end()) return it->second;
    Whole w;
    const CodecSettings codec = whole_codec(rung);
    w.trial.compressed = compress_matrix(exact_, n_, codec, progress_, executor_);
    w.trial.errors = measure_compression(exact_, w.trial.compressed, probe_, &w.map, progress_);
    record(codec.kept_fraction, w.trial.errors, w.trial.compressed.total_bytes(), n_);
    return whole_[rung] = std::move(w);
  }

  void record(double kept_fraction, const CompressionErrors& e, std::size_t bytes,
              std::size_t rows) {
    s_.trials.push_back({kept_fraction, e.matrix.rel_frobenius, e.indirect, bytes, rows});
  }

  const std::vector<const float*>& exact_;
  std::size_t n_;
  CodecSettings codec_;
  const IndirectLightProbe& probe_;
  double budget_;
  MatrixStorage& s_;
  Progress* progress_;
  CompressionExecutor* executor_;
  std::map<int, double> sampled_;
  std::map<int, Whole> whole_;
};

// Bisection on rungs [0, top] of the light error on the sample: the smallest
// rung whose sample meets the budget, else the top one.
int search_on_sample(KeptFractionSearch& search, int top, double budget) {
  int lo = 0, hi = top, found = top;
  while (lo <= hi) {
    const int mid = (lo + hi) / 2;
    if (search.sampled_error(mid) <= budget) {
      found = mid;
      hi = mid - 1;
    } else {
      lo = mid + 1;
    }
  }
  return found;
}

// Bisection on rungs [0, top] with the whole matrix compressed at each, for a
// matrix whose sample would be every row: the smallest rung that meets the
// budget, else the top one.
int search_whole(KeptFractionSearch& search, int top) {
  int lo = 0, hi = top, found = top;
  while (lo <= hi) {
    const int mid = (lo + hi) / 2;
    if (search.meets(mid)) {
      found = mid;
      hi = mid - 1;
    } else {
      lo = mid + 1;
    }
  }
  return found;
}

// The sample's error at `rung` scaled by how far the sample was from the
// whole matrix at `measured` (the same rows, so much the same bias): what the
// whole matrix is predicted to give at `rung`.
double predicted_whole_error(KeptFractionSearch& search, int rung, int measured) {
  const double sampled = search.sampled_error(measured);
  if (!(sampled > 0.0)) return search.sampled_error(rung);
  return search.sampled_error(rung) * search.whole_error(measured) / sampled;
}

// Whether the rung below `rung` is worth compressing whole: predicted to meet
// the budget, or hopeful to once its lights are rebalanced (its worst light's
// error brought down to the mean over the lights, as far as rebalancing
// goes). Hope needs lights as unbalanced at `rung` as rebalancing asks for
// (kRebalanceSpread): on lights that even, no rebalancing would be tried.
bool worth_trying_below(KeptFractionSearch& search, int rung, double budget) {
  if (predicted_whole_error(search, rung - 1, rung) <= budget) return true;
  const IndirectLightError& whole = search.whole_light_error(rung);
  if (!lights_unbalanced(whole)) return false;
  const double sampled = search.sampled_error(rung);
  const double hopeful = sampled > 0.0
                             ? search.sampled_error(rung - 1) * whole.rel_rms_mean / sampled
                             : search.sampled_error(rung - 1);
  return hopeful <= budget;
}

// The whole matrix from the rung the sample found. While it misses the
// budget, up the ladder to the first rung predicted to meet it (or the top).
// When it meets it, one rung down if that one is predicted to meet it too.
// Returns the rung kept.
int compress_whole_from(KeptFractionSearch& search, int rung, int top, double budget) {
  const bool missed = !search.meets(rung);
  while (!search.meets(rung) && rung < top) {
    const int measured = rung;
    do {
      ++rung;
    } while (rung < top && predicted_whole_error(search, rung, measured) > budget);
  }
  // After a climb the rung below is known to miss, or predicted to.
  if (missed || rung == 0 || !worth_trying_below(search, rung, budget)) return rung;
  return search.meets(rung - 1) ? rung - 1 : rung;
}

// The smallest kept fraction of the ladder whose light error meets the
// budget within the size limit; when none does, the largest that fits (the
// smallest light error the limit allows), said plainly. The ladder is
// searched on a sample of the rows with one ordering; the whole matrix is
// then compressed at the fraction found, measured, and moved up the ladder
// while it misses the budget (the sample's estimate can be off), so the
// stored matrix's own error is what meets the budget.
Trial search_kept_fraction(const std::vector<const float*>& exact, std::size_t n,
                           const IndirectLightProbe& probe, const BakeSettings& settings,
                           CodecSettings codec, MatrixStorage& s, Progress* progress,
                           Diagnostics& diagnostics, CompressionExecutor* executor) {
  const double budget = settings.error_budget.value_or(BakeSettings::kDefaultErrorBudget);
  const double limit = settings.size_limit.value_or(BakeSettings::kDefaultSizeLimit);
  s.error_budget = budget;
  s.size_limit = limit;
  s.size_limit_bytes =
      static_cast<std::size_t>(std::floor(limit * static_cast<double>(s.dense_rgb_bytes)));
  const int channels = static_cast<int>(exact.size());
  constexpr int kRungs = static_cast<int>(std::size(kKeptFractionLadder));
  // The kept entries' storage, fixed for every trial so that a rung's size is
  // known before compressing: half precision unless some entry of T is
  // beyond a half's range (then every trial would fall back to float32).
  if (!codec.kept_storage) {
    bool fits = true;
    for (const float* a : exact) fits = fits && fits_half(std::span(a, n * n));
    codec.kept_storage = fits ? KeptStorage::kFloat16 : KeptStorage::kFloat32;
  }
  // The rungs that fit.
  int top = -1;
  while (top + 1 < kRungs && predicted_total_bytes(n, channels, kKeptFractionLadder[top + 1],
                                                   *codec.kept_storage) <= s.size_limit_bytes)
    ++top;
  const bool nothing_fits = top < 0;
  if (nothing_fits) top = 0;
  std::vector<std::uint32_t> sample = search_sample_block_rows(n);
  const bool sample_is_whole = sample.size() == (n + 3) / 4;
  if (!sample_is_whole) {
    // One ordering for every sampled trial, computed at the middle of the rungs.
    codec.kept_fraction = kKeptFractionLadder[top / 2];
    codec.permutation = compute_permutation(exact, n, codec, progress);
    codec.block_rows = std::move(sample);
  }
  KeptFractionSearch search(exact, n, codec, probe, budget, s, progress, executor);
  const int best =
      sample_is_whole
          ? search_whole(search, top)
          : compress_whole_from(search, search_on_sample(search, top, budget), top, budget);
  std::vector<float> map;
  Trial passed = search.take(best, map);
  s.error_budget_met = budgeted_light_error(passed.errors.indirect) <= budget;
  const double mib = 1.0 / (1 << 20);
  const auto bytes_text = [&](std::size_t bytes) {
    return text_format("%.1f MiB, %.1fx smaller than dense float32 RGB",
                       static_cast<double>(bytes) * mib,
                       static_cast<double>(s.dense_rgb_bytes) / static_cast<double>(bytes));
  };
  const std::string limit_text = text_format("the size limit (%g of dense float32 RGB: %.1f MiB)",
                                             limit, static_cast<double>(s.size_limit_bytes) * mib);
  const IndirectLightError& light = passed.errors.indirect;
  const std::size_t bytes = passed.compressed.total_bytes();
  if (s.error_budget_met) {
    s.error_budget_outcome = text_format(
        "met: kept fraction %g gives a light error of %.3g on the worst of %zu evaluation "
        "lights (mean %.3g), within the budget %g; %s, within %s",
        kKeptFractionLadder[best], budgeted_light_error(light), light.lights, light.rel_rms_mean,
        budget, bytes_text(bytes).c_str(), limit_text.c_str());
  } else {
    s.error_budget_outcome = text_format(
        "NOT met: %s; kept fraction %g, %s, gives a light error of %.3g on the worst of %zu "
        "evaluation lights (mean %.3g) against the budget %g. Kept that instead; for the "
        "budget, raise 'size_limit' or set 'codec' to dense (exact, %.1f MiB)",
        nothing_fits ? ("no kept fraction fits " + limit_text).c_str()
                     : ("no kept fraction within " + limit_text + " meets it").c_str(),
        kKeptFractionLadder[best], bytes_text(bytes).c_str(), budgeted_light_error(light),
        light.lights, light.rel_rms_mean, budget, static_cast<double>(s.dense_bytes) * mib);
    diagnostics.warn("compress", "error budget " + s.error_budget_outcome);
  }
  if (passed.errors.indirect.lights == 0)
    diagnostics.warn("compress",
                     "no evaluation light puts any indirect light on the patches: the light "
                     "error is zero whatever is kept and the budget chose the smallest kept "
                     "fraction");
  s.abs_error_sum = std::move(map);
  const std::string tried =
      sample_is_whole
          ? text_format("%zu of the %d kept fractions that fit, each on the whole matrix",
                        s.trials.size(), top + 1)
          : text_format(
                "%zu of the %d kept fractions that fit measured on a sample of %zu of the "
                "%zu patch rows, then the whole matrix compressed at %zu of them",
                search.sampled_count(), top + 1, s.trials.front().rows, n,
                s.trials.size() - search.sampled_count());
  s.decisions.push_back({text_format("kept fraction: %g", kKeptFractionLadder[best]),
                         text_format("error budget %g on the indirect light (%s): %s", budget,
                                     tried.c_str(), s.error_budget_outcome.c_str())});
  return passed;
}

}  // namespace

std::vector<std::uint32_t> search_sample_block_rows(std::size_t n) {
  const std::size_t block_rows = (n + 3) / 4;
  const std::size_t stride =
      std::clamp<std::size_t>(block_rows / kSearchSampleMinBlockRows, 1, kSearchSampleStride);
  // Similar rows sit together after ordering: a stride takes some of each kind.
  std::vector<std::uint32_t> sample;
  for (std::size_t b = stride / 2; b < block_rows; b += stride)
    sample.push_back(static_cast<std::uint32_t>(b));
  return sample;
}

std::vector<const float*> stored_channels(const TransportResult& transport) {
  std::vector<const float*> m;
  for (const ChannelTransport& c : transport.channels) m.push_back(c.t.data());
  return m;
}

std::array<int, 3> channel_of_rgb(const TransportResult& transport) {
  std::array<int, 3> map{0, 0, 0};
  for (std::size_t c = 0; c < transport.channels.size(); ++c)
    for (int k : transport.channels[c].rgb) map[static_cast<std::size_t>(k)] = static_cast<int>(c);
  return map;
}

MatrixStorage store_transport(const TransportResult& transport, const IndirectLightProbe& probe,
                              const BakeSettings& settings, Progress* progress,
                              Diagnostics& diagnostics, CompressionExecutor* executor) {
  return store_matrices(stored_channels(transport), transport.n, probe, settings, progress,
                        diagnostics, executor);
}

MatrixStorage store_matrices(const std::vector<const float*>& exact, std::size_t n,
                             const IndirectLightProbe& probe, const BakeSettings& settings,
                             Progress* progress, Diagnostics& diagnostics,
                             CompressionExecutor* executor) {
  const auto start = Clock::now();
  MatrixStorage s;
  s.dense_bytes = exact.size() * n * n * sizeof(float);
  s.dense_rgb_bytes = 3 * n * n * sizeof(float);

  CodecChoice choice = settings.codec;
  if (choice == CodecChoice::Auto) {
    if (s.dense_bytes <= BakeSettings::kDenseUpToBytes) {
      choice = CodecChoice::Dense;
      const std::string why = text_format(
          "the dense float32 matrix is only %.2f MiB (compression pays above %.0f MiB): a dense "
          "product is cheap at %zu patches and compression would only add error",
          static_cast<double>(s.dense_bytes) / (1 << 20),
          static_cast<double>(BakeSettings::kDenseUpToBytes) / (1 << 20), n);
      s.decisions.push_back({"codec: dense", why});
      diagnostics.left_out("compress", "compression of the transport matrix: " + why);
    } else {
      choice = CodecChoice::LightWeighted;
      s.decisions.push_back(
          {"codec: ours", text_format("the dense float32 matrix would take %.1f MiB",
                                      static_cast<double>(s.dense_bytes) / (1 << 20))});
    }
  } else {
    s.decisions.push_back({std::string("codec: ") + to_string(choice), "requested"});
  }
  s.codec = to_string(choice);

  if (choice == CodecChoice::Dense) {
    s.stored_bytes = s.dense_bytes;
    s.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return s;
  }

  if (executor)
    s.decisions.push_back({"block encoding: " + executor->description(), "distributed bake"});
  CodecSettings codec;
  codec.kind =
      choice == CodecChoice::LargestEntries ? CodecKind::LargestEntries : CodecKind::LightWeighted;
  codec.ordering = settings.ordering;
  // The light-weighted codec spends its bytes where the evaluation lights'
  // light goes.
  EntryImportance importance;
  if (codec.kind == CodecKind::LightWeighted) {
    importance = light_importance(exact, n, probe.first_hit, probe.channel_of_rgb, probe.area);
    codec.importance = &importance;
    s.decisions.push_back(
        {"kept entries and block weights: by the light they carry",
         text_format("each entry weighted by its row's patch area and by how much light its "
                     "column carries over the %zu evaluation lights (floor %g of the mean)",
                     probe.first_hit.size(), static_cast<double>(kColumnWeightFloor))});
  }
  Trial chosen;
  if (settings.kept_fraction || choice == CodecChoice::LargestEntries) {
    codec.kept_fraction = settings.kept_fraction.value_or(kPaperKeptFraction);
    s.decisions.push_back(
        {text_format("kept fraction: %g", codec.kept_fraction),
         settings.kept_fraction ? "requested" : "the published pipeline keeps 4% of the entries"});
    chosen = compress_for_light(exact, n, codec, probe, &s.abs_error_sum, progress, executor);
  } else {
    chosen =
        search_kept_fraction(exact, n, probe, settings, codec, s, progress, diagnostics, executor);
  }
  s.errors = chosen.errors;
  s.stored_bytes = chosen.compressed.total_bytes();
  s.decisions.push_back(
      {text_format("ordering: %s, encoder: %s, format: %s", chosen.compressed.ordering.c_str(),
                   chosen.compressed.encoder.c_str(),
                   chosen.compressed.format == DdsFormat::kBc4 ? "BC4" : "BC1"),
       settings.ordering ? "ordering requested"
       : choice == CodecChoice::LargestEntries
           ? "the published pipeline"
           : (chosen.compressed.format == DdsFormat::kBc4
                  ? "one (grey) channel: BC4 spends the block's 8 bytes on it"
                  : "colour: three channels in one BC1 block")});
  s.compressed = std::move(chosen.compressed);
  s.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return s;
}

}  // namespace bounce
