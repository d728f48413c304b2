#pragma once
// BC1 (DXT1) 4x4 blocks: the block format of the compressed transport matrix.
// A block is 8 bytes: two RGB565 endpoints c0, c1 (little-endian)
// and 16 2-bit indices (texel y*4+x at bits 2(y*4+x) of the little-endian
// word in bytes 4..7). c0 > c1 (as 16-bit numbers) selects 4-colour mode
// {c0, c1, (2c0+c1)/3, (c0+2c1)/3}; c0 <= c1 selects 3-colour mode
// {c0, c1, (c0+c1)/2, black}. Black is code 0, which decodes to value 0.
//
// Texels are 8-bit codes of the log-quantised matrix (R, G, B = the three
// colour channels). "Error" everywhere in this module is the weighted
// squared error in code space, sum over texels and channels of
// weight * (decoded - target)^2; weight 0 marks a "hole" (a kept entry that
// the exact sparse part replaces at decode), whose decoded value is free.
#include <cstddef>
#include <cstdint>

namespace bounce {

inline constexpr std::size_t kBc1BlockBytes = 8;

// Decodes one block exactly as libsquish 1.15 does (squish::Decompress with
// kDxt1): 565 -> 888 by bit replication, 1/3 and 2/3 points and the midpoint
// by truncating integer division. Tested bit for bit against libsquish.
void decode_bc1_block(const std::uint8_t* block, std::uint8_t rgb[16][3]);

// Our encoder: minimises the weighted squared error above. Weights may span
// many decades within a block (the caller passes weight ~ value^2 so that the
// error after the inverse log transform is what is minimised); only their
// ratios matter. Negative or NaN weights count as 0.
void encode_bc1_block_weighted(const std::uint8_t rgb[16][3], const float weight[16][3],
                               std::uint8_t out[8]);

// Weighted squared error of a block against its target (weight nullptr: all 1).
double bc1_block_error(const std::uint8_t rgb[16][3], const float weight[16][3],
                       const std::uint8_t block[8]);

// Every encoder the project compares. Baselines ignore weights except the
// masked one, which tells libsquish to ignore texels whose weights are all 0.
// libsquish runs with its default uniform channel metric (1, 1, 1): the three
// channels are three matrices of equal importance, not perceived colours.
enum class Bc1Encoder {
  kWeighted,                   // ours (encode_bc1_block_weighted)
  kSquishClusterFit,           // squish::Compress(kDxt1 | kColourClusterFit)
  kSquishClusterFitMasked,     // squish::CompressMasked, holes masked out
  kSquishIterativeClusterFit,  // squish::Compress(kDxt1 | kColourIterativeClusterFit)
  kSquishRangeFit,             // squish::Compress(kDxt1 | kColourRangeFit)
  kStbHighQuality,             // stb_compress_dxt_block(alpha 0, STB_DXT_HIGHQUAL)
};
inline constexpr Bc1Encoder kAllBc1Encoders[] = {Bc1Encoder::kWeighted,
                                                 Bc1Encoder::kSquishClusterFit,
                                                 Bc1Encoder::kSquishClusterFitMasked,
                                                 Bc1Encoder::kSquishIterativeClusterFit,
                                                 Bc1Encoder::kSquishRangeFit,
                                                 Bc1Encoder::kStbHighQuality};

// Stable lower-case names for reports and command-line options:
// "weighted", "squish-cluster", "squish-cluster-masked", "squish-iterative",
// "squish-range", "stb-hq".
const char* bc1_encoder_name(Bc1Encoder encoder);
// Inverse of bc1_encoder_name; throws bounce::Error listing the valid names.
Bc1Encoder bc1_encoder_from_name(const char* name);

// One block with any encoder. weight may be nullptr (all texels count 1).
void encode_bc1_block(Bc1Encoder encoder, const std::uint8_t rgb[16][3], const float weight[16][3],
                      std::uint8_t out[8]);

}  // namespace bounce
