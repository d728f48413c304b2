#include "io/npy.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>

#include "base/checked_size.h"
#include "base/mapped_buffer.h"
#include "io/atomic_file.h"

namespace bounce {

namespace fs = std::filesystem;

namespace {

static_assert(std::endian::native == std::endian::little, "npy writer assumes little-endian");

std::string shape_string(const std::vector<std::size_t>& shape) {
  std::string s = "(";
  for (std::size_t k = 0; k < shape.size(); ++k) {
    s += std::to_string(shape[k]);
    if (shape.size() == 1 || k + 1 < shape.size()) s += ",";
    if (k + 1 < shape.size()) s += " ";
  }
  return s + ")";
}

std::size_t element_count(const std::vector<std::size_t>& shape) {
  const auto n = checked_product(shape);
  return n ? *n : std::numeric_limits<std::size_t>::max();
}

// The data is the concatenation of `parts` (pointer, bytes).
using RawParts = std::vector<std::pair<const void*, std::size_t>>;

void write_raw(const fs::path& path, const char* descr, const RawParts& parts, std::size_t elements,
               const std::vector<std::size_t>& shape) {
  if (element_count(shape) != elements)
    throw NpyError(path.string(), "shape " + shape_string(shape) + " does not match " +
                                      std::to_string(elements) + " elements");
  std::string header = std::string("{'descr': '") + descr +
                       "', 'fortran_order': False, 'shape': " + shape_string(shape) + ", }";
  // Magic (6) + version (2) + header length (2) + header, padded with spaces
  // and ending in '\n' so the data starts on a 64-byte boundary.
  const std::size_t unpadded = 10 + header.size() + 1;
  header.append((64 - unpadded % 64) % 64, ' ');
  header.push_back('\n');
  AtomicFile file(path);
  auto& out = file.stream();
  out.write("\x93NUMPY\x01\x00", 8);
  const auto len = static_cast<std::uint16_t>(header.size());
  out.write(reinterpret_cast<const char*>(&len), 2);
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  // In chunks, each handed back to its file once written when it is a mapped
  // matrix (out-of-core bake), so writing F or T does not make all of it
  // resident again.
  constexpr std::size_t kChunk = std::size_t(64) << 20;
  for (const auto& [data, bytes] : parts)
    for (std::size_t at = 0; at < bytes; at += kChunk) {
      const char* p = static_cast<const char*>(data) + at;
      const std::size_t count = std::min(kChunk, bytes - at);
      out.write(p, static_cast<std::streamsize>(count));
      release_residency(p, count);
    }
  file.commit();
}

// One dimension of a header's shape: decimal digits only, surrounded by
// spaces (what NumPy writes). std::stoull alone would accept "-1" (as
// 2^64 - 1) and trailing junk.
std::optional<std::size_t> parse_dimension(const std::string& item) {
  const auto first = item.find_first_not_of(' ');
  const auto last = item.find_last_not_of(' ');
  if (first == std::string::npos) return std::nullopt;
  std::size_t value = 0;
  for (std::size_t k = first; k <= last; ++k) {
    const char c = item[k];
    if (c < '0' || c > '9') return std::nullopt;
    const auto next = checked_product(value, 10);
    if (!next || *next > std::numeric_limits<std::size_t>::max() - std::size_t(c - '0'))
      return std::nullopt;
    value = *next + std::size_t(c - '0');
  }
  return value;
}

template <typename T>
NpyArray<T> read_typed(const fs::path& path, const char* want) {
  // Every size below comes from the file and is checked against the file's
  // real size before anything is allocated: a few bytes of header must not
  // be able to ask for gigabytes.
  const std::size_t file_size = regular_file_size<NpyError>(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw NpyError(path.string(), "cannot open file");
  char magic[8];
  in.read(magic, 8);
  if (!in || std::memcmp(magic, "\x93NUMPY", 6) != 0)
    throw NpyError(path.string(), "not a .npy file (bad magic)");
  std::size_t header_len = 0, prefix = 0;
  if (magic[6] == 1) {
    std::uint16_t l = 0;
    in.read(reinterpret_cast<char*>(&l), 2);
    header_len = l;
    prefix = 10;
  } else if (magic[6] == 2 || magic[6] == 3) {
    std::uint32_t l = 0;
    in.read(reinterpret_cast<char*>(&l), 4);
    header_len = l;
    prefix = 12;
  } else {
    throw NpyError(path.string(), "unsupported .npy version " + std::to_string(magic[6]));
  }
  if (!in || header_len > file_size - std::min(file_size, prefix))
    throw NpyError(path.string(), "truncated header: header length " + std::to_string(header_len) +
                                      ", file has " + std::to_string(file_size) + " bytes");
  std::string header(header_len, '\0');
  in.read(header.data(), static_cast<std::streamsize>(header_len));
  if (!in) throw NpyError(path.string(), "truncated header");
  if (header.find(std::string("'descr': '") + want + "'") == std::string::npos)
    throw NpyError(path.string(),
                   std::string("wrong dtype, expected ") + want + " in header " + header);
  if (header.find("'fortran_order': False") == std::string::npos)
    throw NpyError(path.string(), "Fortran-order arrays are not supported");
  const auto open = header.find("'shape': (");
  const auto close = open == std::string::npos ? open : header.find(')', open);
  if (open == std::string::npos || close == std::string::npos)
    throw NpyError(path.string(), "header has no shape");
  NpyArray<T> a;
  std::stringstream dims(header.substr(open + 10, close - open - 10));
  std::string item;
  while (std::getline(dims, item, ',')) {
    if (item.find_first_not_of(' ') == std::string::npos) continue;
    const auto d = parse_dimension(item);
    if (!d) throw NpyError(path.string(), "header field 'shape': bad dimension '" + item + "'");
    a.shape.push_back(*d);
  }
  const auto n = checked_product(a.shape);
  const auto bytes = n ? checked_product(*n, sizeof(T)) : std::nullopt;
  if (!bytes)
    throw NpyError(path.string(), "header field 'shape' " + shape_string(a.shape) +
                                      ": the element count overflows 64 bits");
  const std::size_t available = file_size - (prefix + header_len);
  if (available < *bytes)
    throw NpyError(path.string(), "truncated: header field 'shape' " + shape_string(a.shape) +
                                      " needs " + std::to_string(*bytes) +
                                      " bytes of data, file has " + std::to_string(available));
  a.data.resize(*n);
  in.read(reinterpret_cast<char*>(a.data.data()), static_cast<std::streamsize>(*bytes));
  if (!in) throw NpyError(path.string(), "read failed");
  return a;
}

}  // namespace

void write_npy(const fs::path& path, std::span<const float> data, std::vector<std::size_t> shape) {
  write_raw(path, "<f4", {{data.data(), data.size_bytes()}}, data.size(), shape);
}
void write_npy(const fs::path& path, const std::vector<std::span<const float>>& parts,
               std::vector<std::size_t> shape) {
  RawParts raw;
  std::size_t elements = 0;
  for (std::span<const float> p : parts) {
    raw.emplace_back(p.data(), p.size_bytes());
    elements += p.size();
  }
  write_raw(path, "<f4", raw, elements, shape);
}
void write_npy(const fs::path& path, std::span<const std::uint32_t> data,
               std::vector<std::size_t> shape) {
  write_raw(path, "<u4", {{data.data(), data.size_bytes()}}, data.size(), shape);
}
void write_npy(const fs::path& path, std::span<const std::int32_t> data,
               std::vector<std::size_t> shape) {
  write_raw(path, "<i4", {{data.data(), data.size_bytes()}}, data.size(), shape);
}

void write_npy(const fs::path& path, std::span<const std::uint16_t> data,
               std::vector<std::size_t> shape) {
  write_raw(path, "<u2", {{data.data(), data.size_bytes()}}, data.size(), shape);
}
void write_npy_half(const fs::path& path, std::span<const std::uint16_t> bits,
                    std::vector<std::size_t> shape) {
  write_raw(path, "<f2", {{bits.data(), bits.size_bytes()}}, bits.size(), shape);
}

NpyArray<float> read_npy_f32(const fs::path& path) { return read_typed<float>(path, "<f4"); }
NpyArray<std::uint32_t> read_npy_u32(const fs::path& path) {
  return read_typed<std::uint32_t>(path, "<u4");
}
NpyArray<std::int32_t> read_npy_i32(const fs::path& path) {
  return read_typed<std::int32_t>(path, "<i4");
}
NpyArray<std::uint16_t> read_npy_u16(const fs::path& path) {
  return read_typed<std::uint16_t>(path, "<u2");
}
NpyArray<std::uint16_t> read_npy_half_bits(const fs::path& path) {
  return read_typed<std::uint16_t>(path, "<f2");
}

}  // namespace bounce
