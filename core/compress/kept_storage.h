#pragma once
// How a compressed matrix's kept entries are stored in a bake folder.
//
//   float32: uint32 columns and float32 values, 8 bytes an entry: the
//            published pipeline's exact entries.
//   float16: uint16 columns (n <= 65536; uint32 above) and IEEE half values,
//            4 bytes an entry: twice the entries in the same bytes. A half
//            keeps 11 significant bits, so each kept value is off by at most
//            2^-11 of itself after rounding to nearest, 0.05%: a light error
//            of that order at most, two orders below the error budgets the
//            kept entries buy (1-5%), while the block codes they replace are
//            off by several percent. Values a half cannot hold (above 65504)
//            keep the matrix in float32.
//
// The codec rounds the kept values when it makes them, so the matrix in
// memory, its measured error and the files are the same numbers.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace bounce {

enum class KeptStorage { kFloat32, kFloat16 };

const char* kept_storage_name(KeptStorage storage);
// "float32" or "float16"; nullopt for anything else.
std::optional<KeptStorage> parse_kept_storage(const std::string& name);

// Whether an n x n matrix's columns fit uint16 in this storage.
bool kept_columns_are_short(KeptStorage storage, std::size_t n);
// Bytes of one kept entry (column and value) of an n x n matrix.
std::size_t kept_entry_bytes(KeptStorage storage, std::size_t n);

// Whether every value is finite and within a half's range (|v| <= 65504).
bool fits_half(std::span<const float> values);
// Each value rounded to the nearest half (ties to even), back as a float.
void round_to_half(std::span<float> values);
// The bits of each value as a half, and back; every value must fit.
void to_half_bits(std::span<const float> values, std::span<std::uint16_t> bits);
void from_half_bits(std::span<const std::uint16_t> bits, std::span<float> values);

}  // namespace bounce
