#include "compress/codec.h"

#include <algorithm>
#include <chrono>
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
  for (const CsrMatrix& k : kept) b += k.bytes();
  return b;
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

CompressedMatrix compress_matrix(const std::vector<const float*>& matrices, std::size_t n,
                                 const CodecSettings& settings, Progress* progress,
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
  for (std::size_t c = 0; c < matrices.size(); ++c) {
    const float* a = matrices[c];
    const float threshold = kept_threshold(a, n, settings.kept_fraction);
    m.kept.push_back(extract_kept(a, n, threshold));
    LogQuantizer q;
    for (std::size_t k = 0; k < n * n; ++k)
      if (a[k] < threshold) q.vmax = std::max(q.vmax, a[k]);
    if (!paper) {
      q.range = fitted_log_range(a, n * n, q.vmax, kOursRangeQuantile);
      q.nearest_at_zero = true;
    }
    m.quantizers.push_back(q);
    for (std::size_t k = 0; k < n * n; ++k) {
      const bool hole = !(a[k] < threshold);
      const std::uint8_t code = hole ? 0 : q.encode(a[k]);
      // A hole's value is replaced by the kept one at decode: any code will
      // do there, so it weighs nothing (ours). The paper encodes it as 0.
      const float w = hole ? 0.0f : q.weight(code);
      // Grey scene with BC1 (paper): the one matrix in R, G and B.
      const std::size_t copies = image_channels == 3 && matrices.size() == 1 ? 3 : 1;
      for (std::size_t r = 0; r < copies; ++r) {
        codes[k * image_channels + c + r] = code;
        weights[k * image_channels + c + r] = w;
      }
    }
    if (progress) progress->advance();
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

void decompress_channel(const CompressedMatrix& m, int c, float* out) {
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
  const CsrMatrix& kept = m.kept[static_cast<std::size_t>(c)];
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t k = kept.row_ptr[i]; k < kept.row_ptr[i + 1]; ++k)
      out[i * n + kept.col[k]] = kept.value[k];
}

}  // namespace bounce
