#pragma once
// Everything a picture of one compressed matrix's error is drawn from, made
// in one call so that a front end only shows it: the per-entry error |T~ -
// T| (summed over the stored channels) and its picture in the stored
// (reordered) order, the error summed per 4x4 block of the stored matrix and
// its picture, and the exact and decoded entries averaged over the stored
// channels, for reading one block's values. Decoding and summing n x n
// entries per channel takes long on large bakes: run it away from a user
// interface's thread.
#include <cstddef>
#include <string>
#include <vector>

#include "compress/codec.h"
#include "compress/compression_error.h"
#include "io/png_writer.h"

namespace bounce {

struct CompressionErrorMaps {
  CompressionErrors errors;      // as given
  std::vector<float> abs_error;  // sum over stored channels of |T~ - T|, n x n, patch order
  // The exact and decoded matrices averaged over the stored channels (n x
  // n, patch order).
  std::vector<float> exact_mean, decoded_mean;
  // |T~ - T| summed per 4x4 block of the stored matrix (blocks x blocks).
  std::vector<float> block_sums;
  std::size_t blocks = 0;
  // matrix_picture of abs_error in the stored order, and of block_sums, at
  // most picture_size pixels a side, with their captions.
  Rgb8Image entry_picture, block_picture;
  std::string entry_title, block_title;
};

// `exact[c]`: stored channel c of the exact matrix (n x n, row-major, patch
// order); `errors` and `abs_error` as measure_compression gives them for
// `compressed` (the sums per entry, n x n). Throws bounce::Error when the
// channels or sizes do not fit the matrix.
CompressionErrorMaps compression_error_maps(const std::vector<const float*>& exact, std::size_t n,
                                            const CompressedMatrix& compressed,
                                            const CompressionErrors& errors,
                                            std::vector<float> abs_error, int picture_size);

}  // namespace bounce
