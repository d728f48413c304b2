#pragma once
// The compressed matrix of a bake folder decoded with code independent of
// the library's: libsquish's BC decoder, the paper's log formula written out,
// the CSR and permutation read from .npy.
#include <squish.h>

#include <cmath>
#include <string>
#include <vector>

#include "cli_harness.h"

namespace bounce::itest {

struct Decoded {
  std::size_t n = 0;
  std::vector<std::vector<float>> channels;  // dense n x n per stored channel, patch order
};

// Rebuilds T~ from T.dds, permutation.npy, T_kept_*.npy and the manifest's
// quantiser parameters.
inline Decoded decode_bake(const fs::path& bake, const json& compression) {
  Decoded d;
  const auto perm = read_npy_u32(bake / "permutation.npy");
  d.n = perm.data.size();
  const auto padded = compression["padded_size"].get<std::size_t>();
  const bool bc4 = compression["format"] == "BC4";
  // DDS: 128-byte header, then the blocks.
  const std::string file = read_text(bake / "T.dds");
  const std::size_t blocks = padded / 4 * padded / 4;
  EXPECT_EQ(file.size(), 128 + 8 * blocks);
  std::vector<squish::u8> rgba(padded * padded * 4);
  squish::DecompressImage(rgba.data(), static_cast<int>(padded), static_cast<int>(padded),
                          file.data() + 128, bc4 ? squish::kBc4 : squish::kDxt1);
  const int stored = compression["stored_channels"].get<int>();
  for (int c = 0; c < stored; ++c) {
    const json& q = compression["quantizers"][static_cast<std::size_t>(c)];
    const double vmax = q["vmax"].get<double>(), range = q["range"].get<double>();
    std::vector<float> t(d.n * d.n);
    // One stored channel lives in R (BC1) or in the single BC4 channel,
    // which libsquish decodes into R as well.
    const std::size_t offset = stored == 1 ? 0 : static_cast<std::size_t>(c);
    for (std::size_t i = 0; i < d.n; ++i)
      for (std::size_t j = 0; j < d.n; ++j) {
        const int code = rgba[(i * padded + j) * 4 + offset];
        // Paper 000: code = 255 (ln(v / vmax) + R) / R, code 0 = zero.
        const double v = code == 0 ? 0.0 : vmax * std::exp(code * range / 255.0 - range);
        t[perm.data[i] * d.n + perm.data[j]] = static_cast<float>(v);
      }
    const std::string base = "T_kept_" + std::to_string(c);
    const auto row_ptr = read_npy_u32(bake / (base + "_row_ptr.npy"));
    const auto col = read_npy_u32(bake / (base + "_col.npy"));
    const auto value = read_npy_f32(bake / (base + "_value.npy"));
    EXPECT_EQ(row_ptr.data.size(), d.n + 1);
    for (std::size_t i = 0; i < d.n; ++i)
      for (std::uint32_t k = row_ptr.data[i]; k < row_ptr.data[i + 1]; ++k)
        t[i * d.n + col.data[k]] = value.data[k];
    d.channels.push_back(std::move(t));
  }
  return d;
}

}  // namespace bounce::itest
