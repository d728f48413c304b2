#include "bake/matrix_storage.h"

#include <chrono>
#include <cmath>

#include "compress/entry_importance.h"
#include "compress/light_rebalance.h"
#include "transport/text_format.h"

namespace bounce {

namespace {

using Clock = std::chrono::steady_clock;

using Trial = MeasuredCompression;

// The smallest kept fraction of the ladder whose light error meets the
// budget within the size limit; when none does, the largest that fits (the
// smallest light error the limit allows), said plainly.
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
  // The light error falls as more entries are kept: bisect on [0, top]. Only
  // two trials are needed afterwards: the best that met the budget, and the
  // last one tried (the top rung when none met it). Each keeps its error map,
  // so the chosen one is not measured twice.
  int lo = 0, hi = top, best = -1;
  std::optional<Trial> passed, last;
  std::vector<float> passed_map, last_map;
  while (lo <= hi) {
    const int mid = (lo + hi) / 2;
    codec.kept_fraction = kKeptFractionLadder[mid];
    last = compress_for_light(exact, n, codec, probe, &last_map, progress, executor);
    s.trials.push_back({codec.kept_fraction, last->errors.matrix.rel_frobenius,
                        last->errors.indirect, last->compressed.total_bytes()});
    if (budgeted_light_error(last->errors.indirect) <= budget) {
      best = mid;
      hi = mid - 1;
      passed = std::move(last);
      passed_map.swap(last_map);
    } else {
      lo = mid + 1;
    }
  }
  const double mib = 1.0 / (1 << 20);
  const auto bytes_text = [&](std::size_t bytes) {
    return text_format("%.1f MiB, %.1fx smaller than dense float32 RGB",
                       static_cast<double>(bytes) * mib,
                       static_cast<double>(s.dense_rgb_bytes) / static_cast<double>(bytes));
  };
  const std::string limit_text = text_format("the size limit (%g of dense float32 RGB: %.1f MiB)",
                                             limit, static_cast<double>(s.size_limit_bytes) * mib);
  s.error_budget_met = best >= 0;
  if (!s.error_budget_met) {
    best = top;  // bisection that never passes ends on the top rung
    passed = std::move(last);
    passed_map.swap(last_map);
  }
  if (!passed) throw Error("compress", "the kept-fraction search compressed nothing");
  const IndirectLightError& light = passed->errors.indirect;
  const std::size_t bytes = passed->compressed.total_bytes();
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
        "budget, raise --size-limit or use --codec dense (exact, %.1f MiB)",
        nothing_fits ? ("no kept fraction fits " + limit_text).c_str()
                     : ("no kept fraction within " + limit_text + " meets it").c_str(),
        kKeptFractionLadder[best], bytes_text(bytes).c_str(), budgeted_light_error(light),
        light.lights, light.rel_rms_mean, budget, static_cast<double>(s.dense_bytes) * mib);
    diagnostics.warn("compress", "error budget " + s.error_budget_outcome);
  }
  if (passed->errors.indirect.lights == 0)
    diagnostics.warn("compress",
                     "no evaluation light puts any indirect light on the patches: the light "
                     "error is zero whatever is kept and the budget chose the smallest kept "
                     "fraction");
  s.abs_error_sum = std::move(passed_map);
  s.decisions.push_back(
      {text_format("kept fraction: %g", kKeptFractionLadder[best]),
       text_format("error budget %g on the indirect light (%zu of the %d kept fractions tried): "
                   "%s",
                   budget, s.trials.size(), top + 1, s.error_budget_outcome.c_str())});
  return std::move(*passed);
}

}  // namespace

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
      choice = CodecChoice::Ours;
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
  codec.kind = choice == CodecChoice::Paper ? CodecKind::Paper : CodecKind::Ours;
  codec.ordering = settings.ordering;
  // Ours spends its bytes where the evaluation lights' light goes.
  EntryImportance importance;
  if (codec.kind == CodecKind::Ours) {
    importance = light_importance(exact, n, probe.first_hit, probe.channel_of_rgb, probe.area);
    codec.importance = &importance;
    s.decisions.push_back(
        {"kept entries and block weights: by the light they carry",
         text_format("each entry weighted by its row's patch area and by how much light its "
                     "column carries over the %zu evaluation lights (floor %g of the mean)",
                     probe.first_hit.size(), static_cast<double>(kColumnWeightFloor))});
  }
  Trial chosen;
  if (settings.kept_fraction || choice == CodecChoice::Paper) {
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
       : choice == CodecChoice::Paper
           ? "the published pipeline"
           : (chosen.compressed.format == DdsFormat::kBc4
                  ? "one (grey) channel: BC4 spends the block's 8 bytes on it"
                  : "colour: three channels in one BC1 block")});
  s.compressed = std::move(chosen.compressed);
  s.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return s;
}

}  // namespace bounce
