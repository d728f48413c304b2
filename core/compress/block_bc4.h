#pragma once
// BC4 (ATI1, one channel) 4x4 blocks: for grey scenes, whose three transport
// matrices are one, and for the "BC4 per channel" comparison against BC1.
// A block is 8 bytes: endpoints a0, a1 (one byte each) and 16 3-bit indices
// (texel y*4+x at bits 3(y*4+x) of the little-endian 48-bit field in bytes
// 2..7). a0 > a1 selects 8 levels {a0, a1, ((7-i)a0 + i a1)/7, i = 1..6};
// a0 <= a1 selects 6 levels {a0, a1, ((5-i)a0 + i a1)/5, i = 1..4} plus 0
// and 255. Weights have the meaning of block_bc1.h (0 = hole, don't care).
#include <cstddef>
#include <cstdint>

namespace bounce {

inline constexpr std::size_t kBc4BlockBytes = 8;

// Decodes one block exactly as libsquish 1.15 does (squish::Decompress with
// kBc4): interpolated levels by truncating integer division. Tested bit for
// bit against libsquish.
void decode_bc4_block(const std::uint8_t* block, std::uint8_t value[16]);

// Our encoder: minimises sum weight * (decoded - target)^2 over both modes.
void encode_bc4_block_weighted(const std::uint8_t value[16], const float weight[16],
                               std::uint8_t out[8]);

double bc4_block_error(const std::uint8_t value[16], const float weight[16],
                       const std::uint8_t block[8]);

enum class Bc4Encoder {
  kWeighted,  // ours
  kSquish,    // squish::Compress(kBc4) (its DXT5 alpha encoder on the channel)
  kStb,       // stb_compress_bc4_block
};
inline constexpr Bc4Encoder kAllBc4Encoders[] = {Bc4Encoder::kWeighted, Bc4Encoder::kSquish,
                                                 Bc4Encoder::kStb};

// "weighted", "squish", "stb".
const char* bc4_encoder_name(Bc4Encoder encoder);
Bc4Encoder bc4_encoder_from_name(const char* name);  // throws bounce::Error

// weight may be nullptr (all texels count 1).
void encode_bc4_block(Bc4Encoder encoder, const std::uint8_t value[16], const float weight[16],
                      std::uint8_t out[8]);

}  // namespace bounce
