#include "bake/matrix_storage.h"

#include <chrono>
#include <cmath>

#include "transport/text_format.h"

namespace bounce {

namespace {

using Clock = std::chrono::steady_clock;

struct Trial {
  CompressedMatrix compressed;
  CompressionErrors errors;
};

Trial compress_and_measure(const std::vector<const float*>& exact, std::size_t n,
                           const CodecSettings& codec, const IndirectLightProbe& probe,
                           std::vector<float>* abs_error_sum, Progress* progress,
                           CompressionExecutor* executor) {
  Trial t;
  t.compressed = compress_matrix(exact, n, codec, progress, executor);
  t.errors = measure_compression(exact, t.compressed, probe, abs_error_sum, progress);
  return t;
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
  Trial chosen;
  if (settings.kept_fraction || choice == CodecChoice::Paper) {
    codec.kept_fraction = settings.kept_fraction.value_or(0.04);
    s.decisions.push_back(
        {text_format("kept fraction: %g", codec.kept_fraction),
         settings.kept_fraction ? "requested" : "the published pipeline keeps 4% of the entries"});
    chosen = compress_and_measure(exact, n, codec, probe, &s.abs_error_sum, progress, executor);
  } else {
    // The smallest kept fraction of the ladder whose relative Frobenius error
    // meets the budget. The error falls as more entries are kept, so bisect.
    const double budget = settings.error_budget.value_or(BakeSettings::kDefaultErrorBudget);
    s.error_budget = budget;
    constexpr int kRungs = static_cast<int>(std::size(kKeptFractionLadder));
    int lo = 0, hi = kRungs - 1, best = -1;
    // Only two trials are ever needed afterwards: the best that met the
    // budget, and the last one tried (the top rung when none met it). Each
    // keeps its error map, so the chosen one is not measured twice.
    std::optional<Trial> passed, last;
    std::vector<float> passed_map, last_map;
    while (lo <= hi) {
      const int mid = (lo + hi) / 2;
      codec.kept_fraction = kKeptFractionLadder[mid];
      last = compress_and_measure(exact, n, codec, probe, &last_map, progress, executor);
      s.trials.push_back(
          {codec.kept_fraction, last->errors.matrix.rel_frobenius, last->compressed.total_bytes()});
      if (last->errors.matrix.rel_frobenius <= budget) {
        best = mid;
        hi = mid - 1;
        passed = std::move(last);
        passed_map.swap(last_map);
      } else {
        lo = mid + 1;
      }
    }
    if (best < 0) {
      best = kRungs - 1;  // bisection that never passes ends on the top rung
      diagnostics.warn("compress",
                       text_format("no kept fraction up to %g meets the error budget %g (relative "
                                   "Frobenius error %.3g): keeping %g; use --codec dense for an "
                                   "exact matrix",
                                   kKeptFractionLadder[best], budget,
                                   last->errors.matrix.rel_frobenius, kKeptFractionLadder[best]));
      passed = std::move(last);
      passed_map.swap(last_map);
    }
    chosen = std::move(*passed);
    s.abs_error_sum = std::move(passed_map);
    codec.kept_fraction = kKeptFractionLadder[best];
    s.decisions.push_back(
        {text_format("kept fraction: %g", codec.kept_fraction),
         text_format("the smallest of %zu tried whose relative Frobenius error (%.3g) meets the "
                     "error budget %g",
                     s.trials.size(), chosen.errors.matrix.rel_frobenius, budget)});
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
