#include "compress/block_image.h"

#include <string>

#include "base/error.h"

namespace bounce {

namespace {

void check_image(const char* what, std::size_t width, std::size_t height, std::size_t texels_size,
                 std::size_t channels, std::size_t weights_size) {
  if (width % 4 != 0 || height % 4 != 0 || width == 0 || height == 0)
    throw Error(what, "image size " + std::to_string(width) + "x" + std::to_string(height) +
                          " is not a positive multiple of 4 (pad the matrix)");
  if (texels_size != width * height * channels)
    throw Error(what, "expected " + std::to_string(width * height * channels) +
                          " texel bytes, got " + std::to_string(texels_size));
  if (weights_size != 0 && weights_size != width * height * channels)
    throw Error(what, "expected " + std::to_string(width * height * channels) +
                          " weights (or none), got " + std::to_string(weights_size));
}

void check_blocks(const char* what, std::size_t width, std::size_t height, std::size_t size) {
  if (width % 4 != 0 || height % 4 != 0) throw Error(what, "image size is not a multiple of 4");
  if (size != (width / 4) * (height / 4) * 8)
    throw Error(what, "expected " + std::to_string((width / 4) * (height / 4) * 8) +
                          " block bytes, got " + std::to_string(size));
}

}  // namespace

std::vector<std::uint8_t> encode_bc1_image(std::size_t width, std::size_t height,
                                           std::span<const std::uint8_t> rgb,
                                           std::span<const float> weights, Bc1Encoder encoder) {
  check_image("BC1 encode", width, height, rgb.size(), 3, weights.size());
  const std::size_t bw = width / 4, bh = height / 4;
  std::vector<std::uint8_t> out(bw * bh * kBc1BlockBytes);
  const bool weighted = !weights.empty();
  // Dynamic schedule: block cost varies a lot (distinct colours per block).
#pragma omp parallel for schedule(dynamic, 1)
  for (std::ptrdiff_t by = 0; by < static_cast<std::ptrdiff_t>(bh); ++by) {
    std::uint8_t texel[16][3];
    float weight[16][3];
    for (std::size_t bx = 0; bx < bw; ++bx) {
      for (int y = 0; y < 4; ++y) {
        const std::size_t row = (static_cast<std::size_t>(by) * 4 + y) * width + bx * 4;
        for (int x = 0; x < 4; ++x)
          for (int c = 0; c < 3; ++c) {
            texel[y * 4 + x][c] = rgb[(row + x) * 3 + c];
            if (weighted) weight[y * 4 + x][c] = weights[(row + x) * 3 + c];
          }
      }
      encode_bc1_block(encoder, texel, weighted ? weight : nullptr,
                       &out[(static_cast<std::size_t>(by) * bw + bx) * kBc1BlockBytes]);
    }
  }
  return out;
}

std::vector<std::uint8_t> decode_bc1_image(std::size_t width, std::size_t height,
                                           std::span<const std::uint8_t> blocks) {
  check_blocks("BC1 decode", width, height, blocks.size());
  const std::size_t bw = width / 4, bh = height / 4;
  std::vector<std::uint8_t> rgb(width * height * 3);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t by = 0; by < static_cast<std::ptrdiff_t>(bh); ++by) {
    std::uint8_t texel[16][3];
    for (std::size_t bx = 0; bx < bw; ++bx) {
      decode_bc1_block(&blocks[(static_cast<std::size_t>(by) * bw + bx) * kBc1BlockBytes], texel);
      for (int y = 0; y < 4; ++y) {
        const std::size_t row = (static_cast<std::size_t>(by) * 4 + y) * width + bx * 4;
        for (int x = 0; x < 4; ++x)
          for (int c = 0; c < 3; ++c) rgb[(row + x) * 3 + c] = texel[y * 4 + x][c];
      }
    }
  }
  return rgb;
}

double bc1_image_error(std::size_t width, std::size_t height, std::span<const std::uint8_t> rgb,
                       std::span<const float> weights, std::span<const std::uint8_t> blocks) {
  check_image("BC1 error", width, height, rgb.size(), 3, weights.size());
  const std::vector<std::uint8_t> dec = decode_bc1_image(width, height, blocks);
  double total = 0.0;
#pragma omp parallel for reduction(+ : total) schedule(static)
  for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(dec.size()); ++k) {
    const double d = static_cast<double>(dec[k]) - static_cast<double>(rgb[k]);
    total += (weights.empty() ? 1.0 : static_cast<double>(weights[k])) * d * d;
  }
  return total;
}

std::vector<std::uint8_t> encode_bc4_image(std::size_t width, std::size_t height,
                                           std::span<const std::uint8_t> values,
                                           std::span<const float> weights, Bc4Encoder encoder) {
  check_image("BC4 encode", width, height, values.size(), 1, weights.size());
  const std::size_t bw = width / 4, bh = height / 4;
  std::vector<std::uint8_t> out(bw * bh * kBc4BlockBytes);
  const bool weighted = !weights.empty();
#pragma omp parallel for schedule(dynamic, 1)
  for (std::ptrdiff_t by = 0; by < static_cast<std::ptrdiff_t>(bh); ++by) {
    std::uint8_t texel[16];
    float weight[16];
    for (std::size_t bx = 0; bx < bw; ++bx) {
      for (int y = 0; y < 4; ++y) {
        const std::size_t row = (static_cast<std::size_t>(by) * 4 + y) * width + bx * 4;
        for (int x = 0; x < 4; ++x) {
          texel[y * 4 + x] = values[row + x];
          if (weighted) weight[y * 4 + x] = weights[row + x];
        }
      }
      encode_bc4_block(encoder, texel, weighted ? weight : nullptr,
                       &out[(static_cast<std::size_t>(by) * bw + bx) * kBc4BlockBytes]);
    }
  }
  return out;
}

std::vector<std::uint8_t> decode_bc4_image(std::size_t width, std::size_t height,
                                           std::span<const std::uint8_t> blocks) {
  check_blocks("BC4 decode", width, height, blocks.size());
  const std::size_t bw = width / 4, bh = height / 4;
  std::vector<std::uint8_t> values(width * height);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t by = 0; by < static_cast<std::ptrdiff_t>(bh); ++by) {
    std::uint8_t texel[16];
    for (std::size_t bx = 0; bx < bw; ++bx) {
      decode_bc4_block(&blocks[(static_cast<std::size_t>(by) * bw + bx) * kBc4BlockBytes], texel);
      for (int y = 0; y < 4; ++y) {
        const std::size_t row = (static_cast<std::size_t>(by) * 4 + y) * width + bx * 4;
        for (int x = 0; x < 4; ++x) values[row + x] = texel[y * 4 + x];
      }
    }
  }
  return values;
}

double bc4_image_error(std::size_t width, std::size_t height, std::span<const std::uint8_t> values,
                       std::span<const float> weights, std::span<const std::uint8_t> blocks) {
  check_image("BC4 error", width, height, values.size(), 1, weights.size());
  const std::vector<std::uint8_t> dec = decode_bc4_image(width, height, blocks);
  double total = 0.0;
#pragma omp parallel for reduction(+ : total) schedule(static)
  for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(dec.size()); ++k) {
    const double d = static_cast<double>(dec[k]) - static_cast<double>(values[k]);
    total += (weights.empty() ? 1.0 : static_cast<double>(weights[k])) * d * d;
  }
  return total;
}

}  // namespace bounce
