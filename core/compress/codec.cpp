#include "compress/codec.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "base/error.h"
#include "compress/block_image.h"
#include "compress/ordering.h"
#include "compress/ordering_paper.h"

namespace bounce {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

Permutation compute_ordering(OrderingMethod ordering, const std::uint8_t* codes, std::size_t n,
                             std::size_t channels) {
  switch (ordering) {
    case OrderingMethod::None:
      return identity_permutation(n);
    case OrderingMethod::Paper1:
      return paper_ordering(codes, n, channels, 1);
    case OrderingMethod::Paper2:
      return paper_ordering(codes, n, channels, 2);
    case OrderingMethod::Ours: {
      // Code 0 is mostly a hole left by a kept entry, which the encoder
      // ignores: let the ordering ignore it too.
      OrderingSettings os;
      os.sketch.zero_is_hole = true;
      return our_ordering(codes, n, channels, os);
    }
  }
  return identity_permutation(n);
}

// Ours: the log range covers all but the smallest 0.1% of the values (see
// fitted_log_range).
constexpr double kOursRangeQuantile = 0.001;

}  // namespace

std::size_t CompressedMatrix::sparse_bytes() const {
  std::size_t b = 0;
  for (const CsrMatrix& k : kept)
    b +=
        k.row_ptr.size() * sizeof(std::uint32_t) + k.col.size() * kept_entry_bytes(kept_storage, n);
  return b;
}

std::size_t predicted_total_bytes(std::size_t n, int channels, double kept_fraction,
                                  KeptStorage storage) {
  const std::size_t padded = (n + 3) / 4 * 4;
  const auto kept = static_cast<std::size_t>(
      std::llround(kept_fraction * static_cast<double>(n) * static_cast<double>(n)));
  const std::size_t csr = (n + 1) * sizeof(std::uint32_t) + kept * kept_entry_bytes(storage, n);
  return static_cast<std::size_t>(channels) * csr + padded / 4 * (padded / 4) * 8 +
         n * sizeof(std::uint32_t);
}

const char* codec_name(CodecKind kind) { return kind == CodecKind::Paper ? "paper" : "ours"; }

const char* ordering_name(OrderingMethod method) {
  switch (method) {
    case OrderingMethod::None:
      return "none";
    case OrderingMethod::Paper1:
      return "paper-1-pass";
    case OrderingMethod::Paper2:
      return "paper-2-passes";
    case OrderingMethod::Ours:
      return "ours";
  }
  return "?";
}

std::vector<std::uint8_t> encode_block_rows(const BlockEncoding& e, std::size_t count,
                                            std::span<const std::uint8_t> codes,
                                            std::span<const float> weights) {
  if (count == 0) return {};
  const std::size_t width = e.width, height = 4 * count;
  if (e.bc4_per_channel) {
    // One BC4 image per channel of the interleaved texels.
    std::vector<std::uint8_t> out;
    std::vector<std::uint8_t> plane(width * height);
    std::vector<float> plane_weights(width * height);
    if (codes.size() != plane.size() * 3 || weights.size() != plane.size() * 3)
      throw Error("compress", "BC4 per channel: texels do not match the block rows");
    for (std::size_t c = 0; c < 3; ++c) {
      for (std::size_t k = 0; k < width * height; ++k) {
        plane[k] = codes[k * 3 + c];
        plane_weights[k] = weights[k * 3 + c];
      }
      const std::vector<std::uint8_t> b =
          encode_bc4_image(width, height, plane, plane_weights, Bc4Encoder::kWeighted);
      out.insert(out.end(), b.begin(), b.end());
    }
    return out;
  }
  if (e.format == DdsFormat::kBc4)
    return encode_bc4_image(width, height, codes, weights, Bc4Encoder::kWeighted);
  return encode_bc1_image(width, height, codes, weights, e.bc1);
}

void place_block_rows(const BlockEncoding& e, std::size_t first, std::size_t count,
                      std::span<const std::uint8_t> rows, std::span<std::uint8_t> blocks) {
  const std::size_t row_bytes = e.block_row_bytes();
  const std::size_t image_bytes = e.block_rows() * row_bytes;
  if (first + count > e.block_rows() || rows.size() != e.images() * count * row_bytes ||
      blocks.size() != e.images() * image_bytes)
    throw Error("compress", "encoded block rows " + std::to_string(first) + ".." +
                                std::to_string(first + count) + " do not fit the image of " +
                                std::to_string(e.block_rows()) + " block rows");
  for (std::size_t i = 0; i < e.images(); ++i)
    std::copy_n(rows.begin() + static_cast<std::ptrdiff_t>(i * count * row_bytes),
                count * row_bytes,
                blocks.begin() + static_cast<std::ptrdiff_t>(i * image_bytes + first * row_bytes));
}

namespace {

// One compression. `keys`: per stored channel, the n x n key that decides
// which entries are kept (the largest); null: the codec's own (the value, or
// with an EntryImportance the value times the square root of its weight).
CompressedMatrix compress_once(const std::vector<const float*>& matrices, std::size_t n,
                               const CodecSettings& settings,
                               const std::vector<std::vector<float>>* keys, Progress* progress,
                               CompressionExecutor* executor) {
  CompressedMatrix m;
  m.n = n;
  m.padded = (n + 3) / 4 * 4;
  m.channels = static_cast<int>(matrices.size());
  m.codec = codec_name(settings.kind);
  m.kept_fraction = settings.kept_fraction;
  const bool paper = settings.kind == CodecKind::Paper;
  // The paper always encodes RGB with BC1; ours gives a single (grey)
  // channel BC4, which spends the same 8 bytes on one channel.
  const bool planar_bc4 = settings.bc4_per_channel && m.channels > 1;
  const bool bc4 = planar_bc4 || (!paper && m.channels == 1 && !settings.bc1_encoder);
  m.format = bc4 ? DdsFormat::kBc4 : DdsFormat::kBc1;
  // BC4 per channel keeps the three channels interleaved until encoding, so
  // the ordering sees all of them, then encodes each plane on its own.
  const std::size_t image_channels = bc4 && !planar_bc4 ? 1 : 3;
  if (progress) progress->begin_stage("compress: split and quantise", matrices.size());

  // 1. Kept entries and log codes, in patch order.
  auto t = Clock::now();
  std::vector<std::uint8_t> codes(n * n * image_channels, 0);
  std::vector<float> weights(n * n * image_channels, 0.0f);
  const EntryImportance* importance = paper ? nullptr : settings.importance;
  if (importance && (importance->row.size() != n || importance->column.size() != matrices.size()))
    throw Error("compress", "the entry importance does not match the matrices");
  m.light_weighted = importance != nullptr;
  std::vector<float> score;
  for (std::size_t c = 0; c < matrices.size(); ++c) {
    const float* a = matrices[c];
    // What decides which entries are kept: the value itself, or the value
    // times the square root of its squared-error weight (the error an encoded
    // entry would have is proportional to its value).
    const float* key = a;
    if (keys) {
      key = (*keys)[c].data();
    } else if (importance) {
      score.resize(n * n);
      const std::vector<float>& column = importance->column[c];
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
          score[i * n + j] = a[i * n + j] * std::sqrt(importance->row[i] * column[j]);
      key = score.data();
    }
    const float threshold = kept_threshold(key, n, settings.kept_fraction);
    m.kept.push_back(extract_kept(a, n, threshold, key));
    LogQuantizer q;
    for (std::size_t k = 0; k < n * n; ++k)
      if (key[k] < threshold) q.vmax = std::max(q.vmax, a[k]);
    if (!paper) {
      q.range = fitted_log_range(a, n * n, q.vmax, kOursRangeQuantile);
      q.nearest_at_zero = true;
    }
    m.quantizers.push_back(q);
    for (std::size_t k = 0; k < n * n; ++k) {
      const bool hole = !(key[k] < threshold);
      const std::uint8_t code = hole ? 0 : q.encode(a[k]);
      // A hole's value is replaced by the kept one at decode: any code will
      // do there, so it weighs nothing (ours). The paper encodes it as 0.
      float w = hole ? 0.0f : q.weight(code);
      if (importance) w *= importance->weight(c, k / n, k % n);
      // Grey scene with BC1 (paper): the one matrix in R, G and B.
      const std::size_t copies = image_channels == 3 && matrices.size() == 1 ? 3 : 1;
      for (std::size_t r = 0; r < copies; ++r) {
        codes[k * image_channels + c + r] = code;
        weights[k * image_channels + c + r] = w;
      }
    }
    if (progress) progress->advance();
  }
  // Half precision when every kept value fits one (else the exact floats):
  // rounded here, so that what is measured is what the bake folder holds.
  m.kept_storage =
      settings.kept_storage.value_or(paper ? KeptStorage::kFloat32 : KeptStorage::kFloat16);
  if (m.kept_storage == KeptStorage::kFloat16) {
    bool fits = true;
    for (const CsrMatrix& k : m.kept) fits = fits && fits_half(k.value);
    if (fits)
      for (CsrMatrix& k : m.kept) round_to_half(k.value);
    else
      m.kept_storage = KeptStorage::kFloat32;
  }
  m.seconds_split = since(t);
  if (progress) progress->end_stage();

  // 2. One permutation for rows and columns.
  const OrderingMethod ordering =
      settings.ordering.value_or(paper ? OrderingMethod::Paper2 : OrderingMethod::Ours);
  m.ordering = ordering_name(ordering);
  if (progress)
    progress->begin_stage(std::string("compress: order rows (") + m.ordering +
                              (settings.permutation ? ", precomputed)" : ")"),
                          1);
  t = Clock::now();
  if (settings.permutation) {
    if (settings.permutation->size() != n || !is_bijection(*settings.permutation))
      throw Error("compress",
                  "the precomputed permutation (" + std::to_string(settings.permutation->size()) +
                      " entries) is not a permutation of the " + std::to_string(n) + " patches");
    m.permutation = *settings.permutation;
  } else {
    m.permutation = compute_ordering(ordering, codes.data(), n, image_channels);
  }
  m.seconds_ordering = settings.permutation ? 0.0 : since(t);
  if (progress) progress->end_stage();
  if (progress) progress->check();

  // 3. Permute codes and weights into a padded image and encode.
  if (progress) progress->begin_stage("compress: encode blocks", 1);
  t = Clock::now();
  const std::size_t w = m.padded;
  std::vector<std::uint8_t> image(w * w * image_channels, 0);
  std::vector<float> image_weights(w * w * image_channels, 0.0f);  // padding weighs nothing
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t src_row = m.permutation[i];
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t src = (src_row * n + m.permutation[j]) * image_channels;
      const std::size_t dst = (i * w + j) * image_channels;
      for (std::size_t c = 0; c < image_channels; ++c) {
        image[dst + c] = codes[src + c];
        image_weights[dst + c] = weights[src + c];
      }
    }
  }
  BlockEncoding e;
  e.width = w;
  e.format = m.format;
  e.bc4_per_channel = planar_bc4;
  if (planar_bc4) {
    m.encoder = std::string(bc4_encoder_name(Bc4Encoder::kWeighted)) + " BC4 per channel";
  } else if (bc4) {
    m.encoder = bc4_encoder_name(Bc4Encoder::kWeighted);
  } else {
    e.bc1 = settings.bc1_encoder.value_or(paper ? Bc1Encoder::kSquishClusterFit
                                                : Bc1Encoder::kWeighted);
    m.encoder = bc1_encoder_name(e.bc1);
  }
  m.blocks = executor ? executor->encode_blocks(e, image, image_weights)
                      : encode_block_rows(e, e.block_rows(), image, image_weights);
  m.seconds_encoding = since(t);
  if (progress) progress->end_stage();
  return m;
}

// Per stored channel: what each entry's block code decodes to, against the
// exact value, in units of the light it costs: |decoded - exact| times the
// square root of the entry's weight. At a kept entry's hole the blocks hold
// whatever the encoder chose there without looking: that is the error the
// entry would have if it were not kept.
std::vector<std::vector<float>> block_error_keys(const CompressedMatrix& m,
                                                 const std::vector<const float*>& matrices,
                                                 const EntryImportance& importance) {
  const std::size_t n = m.n;
  std::vector<std::vector<float>> keys;
  std::vector<float> decoded(n * n);
  for (std::size_t c = 0; c < matrices.size(); ++c) {
    decode_blocks_of_channel(m, static_cast<int>(c), decoded.data());
    std::vector<float> key(n * n);
    const std::vector<float>& column = importance.column[c];
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        const std::size_t k = i * n + j;
        key[k] = std::abs(decoded[k] - matrices[c][k]) * std::sqrt(importance.row[i] * column[j]);
      }
    keys.push_back(std::move(key));
  }
  return keys;
}

}  // namespace

CompressedMatrix compress_matrix(const std::vector<const float*>& matrices, std::size_t n,
                                 const CodecSettings& settings, Progress* progress,
                                 CompressionExecutor* executor) {
  const int passes = settings.kind == CodecKind::Ours && settings.importance
                         ? std::max(1, settings.kept_passes)
                         : 1;
  CompressedMatrix m = compress_once(matrices, n, settings, nullptr, progress, executor);
  // Later passes: keep the entries the previous pass's blocks got most
  // wrong, in light, with the first pass's ordering (the codes barely change).
  CodecSettings again = settings;
  again.permutation = m.permutation;
  for (int pass = 1; pass < passes; ++pass) {
    const std::vector<std::vector<float>> keys =
        block_error_keys(m, matrices, *settings.importance);
    CompressedMatrix next = compress_once(matrices, n, again, &keys, progress, executor);
    next.ordering = m.ordering;
    next.seconds_split += m.seconds_split;
    next.seconds_ordering = m.seconds_ordering;
    next.seconds_encoding += m.seconds_encoding;
    m = std::move(next);
  }
  m.kept_passes = passes;
  return m;
}

void decode_blocks_of_channel(const CompressedMatrix& m, int c, float* out) {
  const std::size_t n = m.n, w = m.padded;
  const bool bc4 = m.format == DdsFormat::kBc4;
  std::vector<std::uint8_t> decoded;
  if (bc4 && m.channels > 1) {
    // BC4 per channel: channel c's image is the c-th of equal size.
    const std::size_t bytes = m.blocks.size() / static_cast<std::size_t>(m.channels);
    decoded = decode_bc4_image(
        w, w, std::span(m.blocks).subspan(bytes * static_cast<std::size_t>(c), bytes));
  } else {
    decoded = bc4 ? decode_bc4_image(w, w, m.blocks) : decode_bc1_image(w, w, m.blocks);
  }
  const std::size_t stride = bc4 ? 1 : 3;
  // With one stored channel in BC1 (paper, grey scene) R stands for it.
  const std::size_t offset = bc4 || m.channels == 1 ? 0 : static_cast<std::size_t>(c);
  const LogQuantizer& q = m.quantizers[static_cast<std::size_t>(c)];
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      out[m.permutation[i] * n + m.permutation[j]] =
          q.decode(decoded[(i * w + j) * stride + offset]);
}

void decompress_channel(const CompressedMatrix& m, int c, float* out) {
  decode_blocks_of_channel(m, c, out);
  const std::size_t n = m.n;
  const CsrMatrix& kept = m.kept[static_cast<std::size_t>(c)];
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t k = kept.row_ptr[i]; k < kept.row_ptr[i + 1]; ++k)
      out[i * n + kept.col[k]] = kept.value[k];
}

}  // namespace bounce
