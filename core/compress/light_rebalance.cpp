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

}  // namespace

MeasuredCompression compress_for_light(const std::vector<const float*>& exact, std::size_t n,
                                       const CodecSettings& codec, const IndirectLightProbe& probe,
                                       std::vector<float>* abs_error_sum, Progress* progress,
                                       CompressionExecutor* executor) {
  MeasuredCompression t =
      compress_and_measure(exact, n, codec, probe, abs_error_sum, progress, executor);
  if (!codec.importance || t.errors.indirect.lights < 2) return t;
  // Each light counted by its share of the squared error, mean 1 over the
  // lights with indirect light (the others count 0, as before).
  const std::vector<double>& e = t.errors.indirect.per_light;
  double sum2 = 0.0;
  for (double v : e) sum2 += v * v;
  if (!(sum2 > 0.0)) return t;
  std::vector<double> factor;
  for (double v : e) factor.push_back(v * v * static_cast<double>(t.errors.indirect.lights) / sum2);
  const EntryImportance rebalanced =
      light_importance(exact, n, probe.first_hit, probe.channel_of_rgb, probe.area, factor);
  CodecSettings second = codec;
  second.importance = &rebalanced;
  std::vector<float> map;
  MeasuredCompression t2 = compress_and_measure(exact, n, second, probe,
                                                abs_error_sum ? &map : nullptr, progress, executor);
  if (budgeted_light_error(t2.errors.indirect) < budgeted_light_error(t.errors.indirect)) {
    t = std::move(t2);
    t.compressed.lights_rebalanced = true;
    if (abs_error_sum) abs_error_sum->swap(map);
  }
  return t;
}

}  // namespace bounce
