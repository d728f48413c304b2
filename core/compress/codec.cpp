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

CompressedMatrix compress_matrix(const std::vector<const float*>& matrices, std::size_t n,
                                 const CodecSettings& settings, Progress* progress) {
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
  if (planar_bc4) {
    m.encoder = std::string(bc4_encoder_name(Bc4Encoder::kWeighted)) + " BC4 per channel";
    std::vector<std::uint8_t> plane(w * w);
    std::vector<float> plane_weights(w * w);
    for (int c = 0; c < m.channels; ++c) {
      for (std::size_t k = 0; k < w * w; ++k) {
        plane[k] = image[k * 3 + static_cast<std::size_t>(c)];
        plane_weights[k] = image_weights[k * 3 + static_cast<std::size_t>(c)];
      }
      const std::vector<std::uint8_t> b =
          encode_bc4_image(w, w, plane, plane_weights, Bc4Encoder::kWeighted);
      m.blocks.insert(m.blocks.end(), b.begin(), b.end());
    }
  } else if (bc4) {
    m.encoder = bc4_encoder_name(Bc4Encoder::kWeighted);
    m.blocks = encode_bc4_image(w, w, image, image_weights, Bc4Encoder::kWeighted);
  } else {
    const Bc1Encoder enc = settings.bc1_encoder.value_or(paper ? Bc1Encoder::kSquishClusterFit
                                                               : Bc1Encoder::kWeighted);
    m.encoder = bc1_encoder_name(enc);
    m.blocks = encode_bc1_image(w, w, image, image_weights, enc);
  }
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
