#pragma once
// Hand-made .npy files for tests of hostile input: any header, followed by
// any number of data bytes, whatever the header says. write_npy (core/io)
// refuses to write such a file, which is the point.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace bounce::test {

// "{'descr': DESCR, 'fortran_order': False, 'shape': SHAPE, }" as NumPy
// writes it, e.g. npy_header("<f4", "(2, 3)").
inline std::string npy_header(const std::string& descr, const std::string& shape) {
  return "{'descr': '" + descr + "', 'fortran_order': False, 'shape': " + shape + ", }";
}

// A version 1.0 file: magic, `header` padded with spaces to a 64-byte
// boundary and ended by a newline, then `data_bytes` zero bytes.
inline void write_raw_npy(const std::filesystem::path& path, const std::string& header,
                          std::size_t data_bytes) {
  std::string h = header;
  h.append((64 - (10 + h.size() + 1) % 64) % 64, ' ');
  h.push_back('\n');
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write("\x93NUMPY\x01\x00", 8);
  const auto len = static_cast<std::uint16_t>(h.size());
  out.write(reinterpret_cast<const char*>(&len), 2);
  out << h << std::string(data_bytes, '\0');
}

}  // namespace bounce::test
