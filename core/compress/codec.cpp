#include "compress/codec.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <string>

#include "base/error.h"
#include "compress/block_image.h"
#include "compress/changed_blocks.h"
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
    case OrderingMethod::GreedyRowTour:
      return paper_ordering(codes, n, channels, 1);
    case OrderingMethod::GreedyRowThenColumnTour:
      return paper_ordering(codes, n, channels, 2);
    case OrderingMethod::SketchTour: {
      // Code 0 is mostly a hole left by a kept entry, which the encoder
      // ignores: let the ordering ignore it too.
      OrderingSettings os;
      os.sketch.zero_is_hole = true;
      return our_ordering(codes, n, channels, os);
    }
  }
  return identity_permutation(n);
}

// The light-weighted codec: the log range covers all but the smallest 0.1% of the values (see
// fitted_log_range).
constexpr double kLightWeightedRangeQuantile = 0.001;

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

const char* codec_name(CodecKind kind) {
  return kind == CodecKind::LargestEntries ? "paper" : "ours";
}

const char* ordering_name(OrderingMethod method) {
  switch (method) {
    case OrderingMethod::None:
      return "none";
    case OrderingMethod::GreedyRowTour:
      return "paper-1-pass";
    case OrderingMethod::GreedyRowThenColumnTour:
      return "paper-2-passes";
    case OrderingMethod::SketchTour:
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

std::vector<std::uint32_t> CompressedMatrix::rows() const {
  std::vector<std::uint32_t> r;
  if (!sampled()) {
    r.resize(n);
    for (std::size_t i = 0; i < n; ++i) r[i] = static_cast<std::uint32_t>(i);
    return r;
  }
  for (std::uint32_t b : block_rows)
    for (std::size_t i = 4 * std::size_t{b}; i < 4 * std::size_t{b} + 4 && i < n; ++i)
      r.push_back(permutation[i]);
  std::sort(r.begin(), r.end());
  return r;
}

namespace {

// The texels of the whole matrix before ordering, in patch order: codes and
// weights of `channels` per entry, only the covered rows filled.
// Codes and weights per texel, channels interleaved, one texel row per patch
// row split: every row for a whole compression, a sample's rows for a sample
// (an n x n buffer for a sample of an eighth of the rows was mostly zeros,
// written and faulted in for every trial).
struct SplitTexels {
  std::size_t channels = 3;
  std::vector<std::uint8_t> codes;
  std::vector<float> weights;
  std::vector<std::uint32_t> row_slot;  // texel row of each patch row; empty: the same row
  std::size_t row_start(std::size_t i, std::size_t n) const {
    return (row_slot.empty() ? i : std::size_t{row_slot[i]}) * n;
  }
};

// What decides which entries of channel c are kept: the value itself, or the
// value times the square root of its squared-error weight (the error an
// encoded entry would have is proportional to its value), on `rows`.
const float* kept_key(const float* a, std::size_t n, std::size_t c,
                      const EntryImportance* importance, std::span<const std::uint32_t> rows,
                      std::vector<float>& score) {
  if (!importance) return a;
  score.resize(n * n);
  const std::vector<float>& column = importance->column[c];
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const std::size_t i = rows[k];
    const float row = importance->row[i];
    for (std::size_t j = 0; j < n; ++j)
      score[i * n + j] = a[i * n + j] * std::sqrt(row * column[j]);
  }
  return score.data();
}

// The quantiser of the entries of `rows` below the kept threshold.
LogQuantizer fitted_quantizer(const float* a, const float* key, float threshold, std::size_t n,
                              std::span<const std::uint32_t> rows, bool paper) {
  LogQuantizer q;
  float vmax = 0.0f;
#pragma omp parallel for reduction(max : vmax) schedule(static)
  for (std::size_t k = 0; k < rows.size(); ++k)
    for (std::size_t j = rows[k] * n; j < (rows[k] + 1) * n; ++j)
      if (key[j] < threshold) vmax = std::max(vmax, a[j]);
  q.vmax = vmax;
  if (paper) return q;
  if (rows.size() == n) {
    q.range = fitted_log_range(a, n * n, q.vmax, kLightWeightedRangeQuantile);
  } else {
    std::vector<float> values;
    values.reserve(rows.size() * n);
    for (std::uint32_t i : rows) values.insert(values.end(), a + i * n, a + (i + 1) * n);
    q.range = fitted_log_range(values.data(), values.size(), q.vmax, kLightWeightedRangeQuantile);
  }
  q.nearest_at_zero = true;
  return q;
}

// Codes and weights of channel c on `rows` into `texels`.
void quantise_channel(const float* a, const float* key, float threshold, const LogQuantizer& q,
                      std::size_t n, std::size_t c, std::size_t stored_channels,
                      const EntryImportance* importance, std::span<const std::uint32_t> rows,
                      SplitTexels& texels) {
  const std::size_t ic = texels.channels;
  // Grey scene with BC1 (paper): the one matrix in R, G and B.
  const std::size_t copies = ic == 3 && stored_channels == 1 ? 3 : 1;
  // The weight depends on the code alone: one exp per code, not per entry.
  std::array<float, 256> code_weight;
  for (int code = 0; code < 256; ++code)
    code_weight[static_cast<std::size_t>(code)] = q.weight(static_cast<std::uint8_t>(code));
  const float half_code_one = 0.5f * q.decode(1);
#pragma omp parallel for schedule(static)
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::size_t i = rows[r];
    const std::size_t texel_row = texels.row_start(i, n);
    for (std::size_t k = i * n; k < (i + 1) * n; ++k) {
      const std::size_t t = (texel_row + k - i * n) * ic;
      const bool hole = !(key[k] < threshold);
      const std::uint8_t code = hole ? 0 : q.encode(a[k], half_code_one);
      // A hole's value is replaced by the kept one at decode: any code will
      // do there, so it weighs nothing (ours). The paper encodes it as 0.
      float w = hole ? 0.0f : code_weight[code];
      if (importance) w *= importance->weight(c, i, k % n);
      for (std::size_t s = 0; s < copies; ++s) {
        texels.codes[t + c + s] = code;
        texels.weights[t + c + s] = w;
      }
    }
  }
}

// Step 1 of a compression: kept entries, quantisers and texels of `rows`.
// `keys`: per stored channel, the n x n key that decides which entries are
// kept (the largest); null: the codec's own (see kept_key). `quantizers`:
// per stored channel, used instead of fitting them (a later kept pass).
SplitTexels split_and_quantise(const std::vector<const float*>& matrices, std::size_t n,
                               const CodecSettings& settings,
                               const std::vector<std::vector<float>>* keys,
                               const std::vector<LogQuantizer>* quantizers,
                               std::span<const std::uint32_t> rows, std::size_t image_channels,
                               CompressedMatrix& m) {
  const bool paper = settings.kind == CodecKind::LargestEntries;
  const EntryImportance* importance = paper ? nullptr : settings.importance;
  if (importance && (importance->row.size() != n || importance->column.size() != matrices.size()))
    throw Error("compress", "the entry importance does not match the matrices");
  m.light_weighted = importance != nullptr;
  SplitTexels texels;
  texels.channels = image_channels;
  if (rows.size() != n) {
    texels.row_slot.assign(n, 0);
    for (std::size_t r = 0; r < rows.size(); ++r)
      texels.row_slot[rows[r]] = static_cast<std::uint32_t>(r);
  }
  texels.codes.assign(rows.size() * n * image_channels, 0);
  texels.weights.assign(rows.size() * n * image_channels, 0.0f);
  std::vector<float> score;
  for (std::size_t c = 0; c < matrices.size(); ++c) {
    const float* a = matrices[c];
    const float* key = keys ? (*keys)[c].data() : kept_key(a, n, c, importance, rows, score);
    const float threshold = kept_threshold(key, n, rows, settings.kept_fraction);
    m.kept.push_back(extract_kept(a, n, threshold, key, rows));
    m.quantizers.push_back(quantizers ? (*quantizers)[c]
                                      : fitted_quantizer(a, key, threshold, n, rows, paper));
    quantise_channel(a, key, threshold, m.quantizers.back(), n, c, matrices.size(), importance,
                     rows, texels);
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
  return texels;
}

// The block rows a compression encodes: the sample, or every one.
std::vector<std::uint32_t> encoded_block_rows(const CompressedMatrix& m) {
  if (m.sampled()) return m.block_rows;
  std::vector<std::uint32_t> all(m.padded / 4);
  for (std::size_t b = 0; b < all.size(); ++b) all[b] = static_cast<std::uint32_t>(b);
  return all;
}

// Step 3: the texels of the encoded block rows, permuted, one image row after
// another (padding weighs nothing).
void permuted_image(const CompressedMatrix& m, const SplitTexels& texels,
                    std::vector<std::uint8_t>& image, std::vector<float>& image_weights) {
  const std::size_t n = m.n, w = m.padded, ic = texels.channels;
  const std::vector<std::uint32_t> blocks = encoded_block_rows(m);
  image.assign(4 * blocks.size() * w * ic, 0);
  image_weights.assign(image.size(), 0.0f);
#pragma omp parallel for schedule(static)
  for (std::size_t s = 0; s < blocks.size(); ++s)
    for (std::size_t r = 0; r < 4; ++r) {
      const std::size_t i = 4 * std::size_t{blocks[s]} + r;
      if (i >= n) continue;
      const std::size_t src_row = m.permutation[i];
      for (std::size_t j = 0; j < n; ++j) {
        const std::size_t src = (texels.row_start(src_row, n) + m.permutation[j]) * ic;
        const std::size_t dst = ((4 * s + r) * w + j) * ic;
        for (std::size_t c = 0; c < ic; ++c) {
          image[dst + c] = texels.codes[src + c];
          image_weights[dst + c] = texels.weights[src + c];
        }
      }
    }
}

struct ImageLayout {
  bool bc4 = false, planar_bc4 = false;
  std::size_t channels = 3;  // texel channels of the image before encoding
};

ImageLayout image_layout(const CodecSettings& settings, std::size_t stored_channels) {
  const bool paper = settings.kind == CodecKind::LargestEntries;
  ImageLayout l;
  // The paper always encodes RGB with BC1; ours gives a single (grey)
  // channel BC4, which spends the same 8 bytes on one channel.
  l.planar_bc4 = settings.bc4_per_channel && stored_channels > 1;
  l.bc4 = l.planar_bc4 || (!paper && stored_channels == 1 && !settings.bc1_encoder);
  // BC4 per channel keeps the three channels interleaved until encoding, so
  // the ordering sees all of them, then encodes each plane on its own.
  l.channels = l.bc4 && !l.planar_bc4 ? 1 : 3;
  return l;
}

void check_sample(const CodecSettings& settings, std::size_t n) {
  if (settings.block_rows.empty()) return;
  if (!settings.permutation)
    throw Error("compress", "a sample of block rows needs a precomputed permutation");
  const std::size_t block_rows = (n + 3) / 4;
  for (std::size_t k = 0; k < settings.block_rows.size(); ++k)
    if (settings.block_rows[k] >= block_rows ||
        (k > 0 && settings.block_rows[k] <= settings.block_rows[k - 1]))
      throw Error("compress", "the sampled block rows are not ascending block rows of the image");
}

// Step 2: one permutation for rows and columns.
void order_rows(const CodecSettings& settings, const SplitTexels& texels, Progress* progress,
                CompressedMatrix& m) {
  const bool paper = settings.kind == CodecKind::LargestEntries;
  const OrderingMethod ordering = settings.ordering.value_or(
      paper ? OrderingMethod::GreedyRowThenColumnTour : OrderingMethod::SketchTour);
  m.ordering = ordering_name(ordering);
  if (progress)
    progress->begin_stage(std::string("compress: order rows (") + m.ordering +
                              (settings.permutation ? ", precomputed)" : ")"),
                          1);
  const auto t = Clock::now();
  if (settings.permutation) {
    if (settings.permutation->size() != m.n || !is_bijection(*settings.permutation))
      throw Error("compress",
                  "the precomputed permutation (" + std::to_string(settings.permutation->size()) +
                      " entries) is not a permutation of the " + std::to_string(m.n) + " patches");
    m.permutation = *settings.permutation;
  } else {
    m.permutation = compute_ordering(ordering, texels.codes.data(), m.n, texels.channels);
  }
  m.seconds_ordering = settings.permutation ? 0.0 : since(t);
  if (progress) progress->end_stage();
  if (progress) progress->check();
}

// Step 3: the encoded block rows. A distributed executor encodes whole images
// only; a sample is encoded here. With `previous` (a kept pass before this
// one, same quantisers and permutation), only the blocks whose kept entries
// changed are encoded; the others keep previous's bytes.
void encode_image(const CodecSettings& settings, const ImageLayout& layout,
                  const SplitTexels& texels, const CompressedMatrix* previous, Progress* progress,
                  CompressionExecutor* executor, CompressedMatrix& m) {
  if (progress) progress->begin_stage("compress: encode blocks", 1);
  const auto t = Clock::now();
  BlockEncoding e;
  e.width = m.padded;
  e.format = m.format;
  e.bc4_per_channel = layout.planar_bc4;
  if (layout.planar_bc4) {
    m.encoder = std::string(bc4_encoder_name(Bc4Encoder::kWeighted)) + " BC4 per channel";
  } else if (layout.bc4) {
    m.encoder = bc4_encoder_name(Bc4Encoder::kWeighted);
  } else {
    e.bc1 = settings.bc1_encoder.value_or(settings.kind == CodecKind::LargestEntries
                                              ? Bc1Encoder::kSquishClusterFit
                                              : Bc1Encoder::kWeighted);
    m.encoder = bc1_encoder_name(e.bc1);
  }
  if (previous && e.images() == 1) {
    m.blocks = previous->blocks;
    const std::vector<std::size_t> changed = blocks_with_changed_holes(*previous, m);
    encode_blocks_in_place(e, changed, texels.codes, texels.weights, texels.channels, m,
                           texels.row_slot);
    m.blocks_encoded = changed.size();
    m.seconds_encoding = since(t);
    if (progress) progress->end_stage();
    return;
  }
  std::vector<std::uint8_t> image;
  std::vector<float> image_weights;
  permuted_image(m, texels, image, image_weights);
  const std::size_t count = image.size() / (4 * m.padded * texels.channels);
  m.blocks = executor && !m.sampled() ? executor->encode_blocks(e, image, image_weights)
                                      : encode_block_rows(e, count, image, image_weights);
  m.blocks_encoded = m.blocks.size() / 8;
  m.seconds_encoding = since(t);
  if (progress) progress->end_stage();
}

// One compression; `keys` as split_and_quantise. `previous`: the kept pass
// before this one, whose quantisers and unchanged blocks are reused.
CompressedMatrix compress_once(const std::vector<const float*>& matrices, std::size_t n,
                               const CodecSettings& settings,
                               const std::vector<std::vector<float>>* keys,
                               const CompressedMatrix* previous, Progress* progress,
                               CompressionExecutor* executor) {
  check_sample(settings, n);
  CompressedMatrix m;
  m.n = n;
  m.padded = (n + 3) / 4 * 4;
  m.channels = static_cast<int>(matrices.size());
  m.codec = codec_name(settings.kind);
  m.kept_fraction = settings.kept_fraction;
  const ImageLayout layout = image_layout(settings, matrices.size());
  m.format = layout.bc4 ? DdsFormat::kBc4 : DdsFormat::kBc1;
  if (!settings.block_rows.empty()) {
    m.permutation = *settings.permutation;
    m.block_rows = settings.block_rows;
  }
  if (progress) progress->begin_stage("compress: split and quantise", 1);
  auto t = Clock::now();
  const std::vector<std::uint32_t> rows = m.rows();
  const SplitTexels texels =
      split_and_quantise(matrices, n, settings, keys, previous ? &previous->quantizers : nullptr,
                         rows, layout.channels, m);
  m.seconds_split = since(t);
  if (progress) progress->end_stage();
  order_rows(settings, texels, progress, m);
  encode_image(settings, layout, texels, previous, progress, executor, m);
  return m;
}

// Per stored channel: what each entry's block code decodes to, against the
// exact value, in units of the light it costs: |decoded - exact| times the
// square root of the entry's weight. At a kept entry's hole the blocks hold
// whatever the encoder chose there without looking: that is the error the
// entry would have if it were not kept. n x n in patch order; rows the blocks
// do not hold (a sample) are 0.
std::vector<std::vector<float>> block_error_keys(const CompressedMatrix& m,
                                                 const std::vector<const float*>& matrices,
                                                 const EntryImportance& importance) {
  const std::size_t n = m.n;
  const std::vector<std::uint32_t> rows = m.rows();
  std::vector<std::vector<float>> keys;
  std::vector<float> decoded(rows.size() * n);
  for (std::size_t c = 0; c < matrices.size(); ++c) {
    decode_blocks_of_channel(m, static_cast<int>(c), decoded.data());
    std::vector<float> key(n * n, 0.0f);
    const std::vector<float>& column = importance.column[c];
#pragma omp parallel for schedule(static)
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const std::size_t i = rows[r];
      for (std::size_t j = 0; j < n; ++j)
        key[i * n + j] = std::abs(decoded[r * n + j] - matrices[c][i * n + j]) *
                         std::sqrt(importance.row[i] * column[j]);
    }
    keys.push_back(std::move(key));
  }
  return keys;
}

}  // namespace

Permutation compute_permutation(const std::vector<const float*>& matrices, std::size_t n,
                                const CodecSettings& settings, Progress* progress) {
  CodecSettings whole = settings;
  whole.block_rows.clear();
  CompressedMatrix m;
  m.n = n;
  const ImageLayout layout = image_layout(whole, matrices.size());
  const SplitTexels texels =
      split_and_quantise(matrices, n, whole, nullptr, nullptr, m.rows(), layout.channels, m);
  order_rows(whole, texels, progress, m);
  return m.permutation;
}

CompressedMatrix compress_matrix(const std::vector<const float*>& matrices, std::size_t n,
                                 const CodecSettings& settings, Progress* progress,
                                 CompressionExecutor* executor) {
  const int passes = settings.kind == CodecKind::LightWeighted && settings.importance
                         ? std::max(1, settings.kept_passes)
                         : 1;
  CompressedMatrix m = compress_once(matrices, n, settings, nullptr, nullptr, progress, executor);
  // Later passes: keep the entries the previous pass's blocks got most
  // wrong, in light, with the first pass's ordering and quantisers, so that
  // only the blocks whose kept entries changed are encoded again.
  CodecSettings again = settings;
  again.permutation = m.permutation;
  for (int pass = 1; pass < passes; ++pass) {
    const std::vector<std::vector<float>> keys =
        block_error_keys(m, matrices, *settings.importance);
    CompressedMatrix next = compress_once(matrices, n, again, &keys, &m, progress, executor);
    next.ordering = m.ordering;
    next.seconds_split += m.seconds_split;
    next.seconds_ordering = m.seconds_ordering;
    next.seconds_encoding += m.seconds_encoding;
    next.blocks_encoded += m.blocks_encoded;
    m = std::move(next);
  }
  m.kept_passes = passes;
  return m;
}

void decode_blocks_of_channel(const CompressedMatrix& m, int c, float* out) {
  const std::size_t n = m.n, w = m.padded;
  const std::vector<std::uint32_t> blocks = encoded_block_rows(m);
  const std::size_t height = 4 * blocks.size();
  const bool bc4 = m.format == DdsFormat::kBc4;
  std::vector<std::uint8_t> decoded;
  if (bc4 && m.channels > 1) {
    // BC4 per channel: channel c's image is the c-th of equal size.
    const std::size_t bytes = m.blocks.size() / static_cast<std::size_t>(m.channels);
    decoded = decode_bc4_image(
        w, height, std::span(m.blocks).subspan(bytes * static_cast<std::size_t>(c), bytes));
  } else {
    decoded = bc4 ? decode_bc4_image(w, height, m.blocks) : decode_bc1_image(w, height, m.blocks);
  }
  const std::size_t stride = bc4 ? 1 : 3;
  // With one stored channel in BC1 (paper, grey scene) R stands for it.
  const std::size_t offset = bc4 || m.channels == 1 ? 0 : static_cast<std::size_t>(c);
  const LogQuantizer& q = m.quantizers[static_cast<std::size_t>(c)];
  // Output row of each patch (its place among rows()).
  std::vector<std::uint32_t> place(n, 0);
  const std::vector<std::uint32_t> rows = m.rows();
  for (std::size_t k = 0; k < rows.size(); ++k) place[rows[k]] = static_cast<std::uint32_t>(k);
#pragma omp parallel for schedule(static)
  for (std::size_t s = 0; s < blocks.size(); ++s)
    for (std::size_t r = 0; r < 4; ++r) {
      const std::size_t i = 4 * std::size_t{blocks[s]} + r;
      if (i >= n) continue;
      float* row = out + std::size_t{place[m.permutation[i]]} * n;
      const std::uint8_t* texels = decoded.data() + (4 * s + r) * w * stride + offset;
      for (std::size_t j = 0; j < n; ++j) row[m.permutation[j]] = q.decode(texels[j * stride]);
    }
}

void decompress_channel(const CompressedMatrix& m, int c, float* out) {
  decode_blocks_of_channel(m, c, out);
  const std::size_t n = m.n;
  const CsrMatrix& kept = m.kept[static_cast<std::size_t>(c)];
  const std::vector<std::uint32_t> rows = m.rows();
  for (std::size_t k = 0; k < rows.size(); ++k)
    for (std::uint32_t e = kept.row_ptr[rows[k]]; e < kept.row_ptr[rows[k] + 1]; ++e)
      out[k * n + kept.col[e]] = kept.value[e];
}

}  // namespace bounce
