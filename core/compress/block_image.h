#pragma once
// Whole images of BC1 / BC4 blocks. Width and height are multiples of 4 (the
// matrix is padded); blocks are stored in row-major block order, as in a DDS
// file. Encoding runs in parallel over block rows (OpenMP).
//
// Layouts: rgb is width*height*3 bytes (row-major, R G B interleaved);
// weights are width*height*3 floats in the same order (BC1) or width*height
// (BC4); an empty weight span means every texel counts 1.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "compress/block_bc1.h"
#include "compress/block_bc4.h"

namespace bounce {

// Throws bounce::Error if sizes do not match or width/height are not
// multiples of 4.
std::vector<std::uint8_t> encode_bc1_image(std::size_t width, std::size_t height,
                                           std::span<const std::uint8_t> rgb,
                                           std::span<const float> weights, Bc1Encoder encoder);
std::vector<std::uint8_t> decode_bc1_image(std::size_t width, std::size_t height,
                                           std::span<const std::uint8_t> blocks);  // -> rgb
// Sum of weight * (decoded - target)^2 over all texels and channels.
double bc1_image_error(std::size_t width, std::size_t height, std::span<const std::uint8_t> rgb,
                       std::span<const float> weights, std::span<const std::uint8_t> blocks);

std::vector<std::uint8_t> encode_bc4_image(std::size_t width, std::size_t height,
                                           std::span<const std::uint8_t> values,
                                           std::span<const float> weights, Bc4Encoder encoder);
std::vector<std::uint8_t> decode_bc4_image(std::size_t width, std::size_t height,
                                           std::span<const std::uint8_t> blocks);
double bc4_image_error(std::size_t width, std::size_t height, std::span<const std::uint8_t> values,
                       std::span<const float> weights, std::span<const std::uint8_t> blocks);

}  // namespace bounce
