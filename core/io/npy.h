#pragma once
// NumPy .npy files (format version 1.0, little-endian, C order), the format
// of every dense array in a bake folder. Written through AtomicFile so a
// reader never sees half a file.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "base/error.h"

namespace bounce {

class NpyError : public Error {
 public:
  using Error::Error;
};

void write_npy(const std::filesystem::path& path, std::span<const float> data,
               std::vector<std::size_t> shape);
// The concatenation of `parts` as one array (T.npy: the channels one after
// another, each possibly a mapped matrix), without copying them together.
void write_npy(const std::filesystem::path& path, const std::vector<std::span<const float>>& parts,
               std::vector<std::size_t> shape);
void write_npy(const std::filesystem::path& path, std::span<const std::uint32_t> data,
               std::vector<std::size_t> shape);
void write_npy(const std::filesystem::path& path, std::span<const std::int32_t> data,
               std::vector<std::size_t> shape);
void write_npy(const std::filesystem::path& path, std::span<const std::uint16_t> data,
               std::vector<std::size_t> shape);
// IEEE half floats ('<f2'), given as their bits (compress/kept_storage.h).
void write_npy_half(const std::filesystem::path& path, std::span<const std::uint16_t> bits,
                    std::vector<std::size_t> shape);

template <typename T>
struct NpyArray {
  std::vector<std::size_t> shape;
  std::vector<T> data;
};

// Reads a file written as above; throws NpyError naming the file when the
// dtype (must be '<f4', '<u4', '<i4', '<u2' or '<f2' to match the function),
// order or size is wrong.
NpyArray<float> read_npy_f32(const std::filesystem::path& path);
NpyArray<std::uint32_t> read_npy_u32(const std::filesystem::path& path);
NpyArray<std::int32_t> read_npy_i32(const std::filesystem::path& path);
NpyArray<std::uint16_t> read_npy_u16(const std::filesystem::path& path);
// IEEE half floats ('<f2'), as their bits.
NpyArray<std::uint16_t> read_npy_half_bits(const std::filesystem::path& path);

}  // namespace bounce
