#pragma once
// The compressed matrix of a bake folder decoded with code independent of
// the library's: libsquish's BC decoder, the paper's log formula written out,
// the CSR and permutation read from .npy.
#include <squish.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "cli_harness.h"

namespace bounce::itest {

// An IEEE half's value from its bits, written out (1 sign, 5 exponent, 10
// fraction bits; exponent 0: subnormal; 31: infinity or NaN).
inline float half_value(std::uint16_t h) {
  const int sign = h >> 15, exponent = (h >> 10) & 31, fraction = h & 1023;
  double v = exponent == 0    ? std::ldexp(fraction, -24)
             : exponent == 31 ? (fraction ? std::nan("") : INFINITY)
                              : std::ldexp(1024 + fraction, exponent - 25);
  return static_cast<float>(sign ? -v : v);
}

struct Decoded {
  std::size_t n = 0;
  std::vector<std::vector<float>> channels;  // dense n x n per stored channel, patch order
};

// The kept entries of stored channel c as the files hold them: CSR row
// starts, columns and values (float16: half values, and uint16 columns below
// 65537 patches).
struct KeptFiles {
  std::vector<std::uint32_t> row_ptr, col;
  std::vector<float> value;
};
inline KeptFiles read_kept_files(const fs::path& bake, const json& compression, int c,
                                 std::size_t n) {
  const std::string base = "T_kept_" + std::to_string(c);
  KeptFiles k;
  k.row_ptr = read_npy_u32(bake / (base + "_row_ptr.npy")).data;
  const bool half = compression.value("kept_storage", "float32") == "float16";
  if (half && n <= 65536) {
    for (std::uint16_t c16 : read_npy_u16(bake / (base + "_col.npy")).data) k.col.push_back(c16);
  } else {
    k.col = read_npy_u32(bake / (base + "_col.npy")).data;
  }
  if (half) {
    for (std::uint16_t h : read_npy_half_bits(bake / (base + "_value.npy")).data)
      k.value.push_back(half_value(h));
  } else {
    k.value = read_npy_f32(bake / (base + "_value.npy")).data;
  }
  return k;
}

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
    const KeptFiles kept = read_kept_files(bake, compression, c, d.n);
    EXPECT_EQ(kept.row_ptr.size(), d.n + 1);
    for (std::size_t i = 0; i < d.n; ++i)
      for (std::uint32_t k = kept.row_ptr[i]; k < kept.row_ptr[i + 1]; ++k)
        t[i * d.n + kept.col[k]] = kept.value[k];
    d.channels.push_back(std::move(t));
  }
  return d;
}

}  // namespace bounce::itest
