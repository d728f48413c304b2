#include "compress/compression_error_maps.h"

#include <string>

#include "base/error.h"
#include "compress/matrix_picture.h"

namespace bounce {

CompressionErrorMaps compression_error_maps(const std::vector<const float*>& exact, std::size_t n,
                                            const CompressedMatrix& compressed,
                                            const CompressionErrors& errors,
                                            std::vector<float> abs_error, int picture_size) {
  const CompressedMatrix& c = compressed;
  if (exact.size() != static_cast<std::size_t>(c.channels) || c.permutation.size() != n ||
      abs_error.size() != n * n)
    throw Error(
        "compression error maps",
        std::to_string(exact.size()) + " exact channels and " + std::to_string(abs_error.size()) +
            " error entries for a matrix of " + std::to_string(c.channels) + " channels and " +
            std::to_string(c.permutation.size()) + " patches (" + std::to_string(n) + " expected)");
  CompressionErrorMaps m;
  m.errors = errors;
  m.abs_error = std::move(abs_error);
  m.exact_mean.assign(n * n, 0.0f);
  m.decoded_mean.assign(n * n, 0.0f);
  std::vector<float> decoded(n * n);
  const float scale = 1.0f / static_cast<float>(c.channels);
  for (int ch = 0; ch < c.channels; ++ch) {
    decompress_channel(c, ch, decoded.data());
    const float* t = exact[static_cast<std::size_t>(ch)];
    for (std::size_t k = 0; k < n * n; ++k) {
      m.exact_mean[k] += t[k] * scale;
      m.decoded_mean[k] += decoded[k] * scale;
    }
  }
  MatrixPictureSettings s;
  s.max_size = picture_size;
  m.entry_title = s.title = "|T~ - T| per entry, reordered (" + c.ordering + ")";
  m.entry_picture = matrix_picture(m.abs_error.data(), n, s, &c.permutation);
  // Blocks live in the stored (reordered) matrix.
  std::vector<float> stored(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      stored[i * n + j] = m.abs_error[c.permutation[i] * n + c.permutation[j]];
  m.block_sums = block_error_sums(stored.data(), n, m.blocks);
  m.block_title = s.title = "|T~ - T| per 4x4 block of T.dds (" + c.codec + ")";
  m.block_picture = matrix_picture(m.block_sums.data(), m.blocks, s);
  return m;
}

}  // namespace bounce
