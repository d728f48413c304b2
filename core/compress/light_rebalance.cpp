#include "compress/light_rebalance.h"

#include "compress/entry_importance.h"

namespace bounce {

namespace {

MeasuredCompression compress_and_measure(const std::vector<const float*>& exact, std::size_t n,
                                         const CodecSettings& codec,
                                         const IndirectLightProbe& probe,
                                         std::vector<float>* abs_error_sum, Progress* progress,
                                         CompressionExecutor* executor) {
  MeasuredCompression t;
  t.compressed = compress_matrix(exact, n, codec, progress, executor);
  t.errors = measure_compression(exact, t.compressed, probe, abs_error_sum, progress);
  return t;
}

// Each light counted by its share of the squared light error `e`, mean 1 over
// the lights with indirect light (the others count 0); empty when no light
// has an error.
std::vector<double> rebalanced_light_factor(const IndirectLightError& e) {
  double sum2 = 0.0;
  for (double v : e.per_light) sum2 += v * v;
  if (!(sum2 > 0.0)) return {};
  std::vector<double> factor;
  for (double v : e.per_light) factor.push_back(v * v * static_cast<double>(e.lights) / sum2);
  return factor;
}

}  // namespace

MeasuredCompression compress_for_light(const std::vector<const float*>& exact, std::size_t n,
                                       const CodecSettings& codec, const IndirectLightProbe& probe,
                                       std::vector<float>* abs_error_sum, Progress* progress,
                                       CompressionExecutor* executor) {
  return rebalance_for_light(
      compress_and_measure(exact, n, codec, probe, abs_error_sum, progress, executor), exact, n,
      codec, probe, abs_error_sum, progress, executor);
}

MeasuredCompression rebalance_for_light(MeasuredCompression first,
                                        const std::vector<const float*>& exact, std::size_t n,
                                        const CodecSettings& codec, const IndirectLightProbe& probe,
                                        std::vector<float>* abs_error_sum, Progress* progress,
                                        CompressionExecutor* executor) {
  MeasuredCompression t = std::move(first);
  if (!codec.importance || t.errors.indirect.lights < 2 || t.compressed.lights_rebalance_tried)
    return t;
  if (!lights_unbalanced(t.errors.indirect)) return t;
  const std::vector<double> factor = rebalanced_light_factor(t.errors.indirect);
  if (factor.empty()) return t;
  const EntryImportance rebalanced =
      light_importance(exact, n, probe.first_hit, probe.channel_of_rgb, probe.area, factor);
  CodecSettings second = codec;
  second.importance = &rebalanced;
  // The first compression's ordering: the rebalanced weights barely move the codes.
  second.permutation = t.compressed.permutation;
  std::vector<float> map;
  MeasuredCompression t2 = compress_and_measure(exact, n, second, probe,
                                                abs_error_sum ? &map : nullptr, progress, executor);
  t.compressed.lights_rebalance_tried = t2.compressed.lights_rebalance_tried = true;
  if (budgeted_light_error(t2.errors.indirect) < budgeted_light_error(t.errors.indirect)) {
    t2.compressed.seconds_ordering = t.compressed.seconds_ordering;
    t = std::move(t2);
    t.compressed.lights_rebalanced = true;
    if (abs_error_sum) abs_error_sum->swap(map);
  }
  return t;
}

}  // namespace bounce
