#pragma once
// Data and timings for comparing the BC1 block encoders (`bounce bench
// compress` and the block codec tests): a synthetic matrix shaped like a real
// transport matrix, and each encoder's speed and weighted error on it.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "compress/block_bc1.h"

namespace bounce {

// Benchmark data like a real transport matrix: the n x n matrix
// v_ij = exp(-|i-j|/200) (1 + 0.3 sin(i/37) cos(j/53)) times a slowly
// varying albedo per channel, the largest 4% of each channel kept exactly
// (holes, weight 0), the rest log-quantised (R = 25, vmax of the remainder)
// with weight = LogQuantizer::weight(code), i.e. ~ value^2. n must be a
// multiple of 4.
struct BlockBenchData {
  std::size_t n = 0;
  std::vector<std::uint8_t> rgb;  // n*n*3 codes, holes at code 0
  std::vector<float> weights;     // n*n*3
};
BlockBenchData make_block_bench_data(std::size_t n);

struct BlockEncoderTiming {
  std::string encoder;   // bc1_encoder_name / bc4_encoder_name
  double seconds = 0.0;  // wall time of encode_*_image
  double blocks_per_second = 0.0;
  int threads = 1;  // OpenMP threads used
  // CPU time of all threads: a fairer comparison on a loaded machine.
  double cpu_seconds = 0.0;
  double blocks_per_cpu_second = 0.0;
  double error = 0.0;  // weighted squared error (bc1_image_error)
  // error / error of libsquish's cluster fit (or of the first encoder when
  // the cluster fit is not among those measured).
  double error_ratio = 0.0;
};

// Encodes the image with each encoder in turn (parallel over block rows) and
// reports speed and weighted error. Pass kAllBc1Encoders for everything.
std::vector<BlockEncoderTiming> bench_bc1_encoders(std::size_t width, std::size_t height,
                                                   std::span<const std::uint8_t> rgb,
                                                   std::span<const float> weights,
                                                   std::span<const Bc1Encoder> encoders);

}  // namespace bounce
