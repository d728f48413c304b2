#pragma once
// DirectDraw Surface files for block-compressed images: the compressed
// transport matrix of a bake (a standard DDS, so any DDS reader opens it).
//
// Written: the classic 128-byte header (magic "DDS " + DDS_HEADER), one mip
// level, linear size set, DDPF_FOURCC pixel format:
//   BC1 -> FourCC 'DXT1' (read by every DDS reader; OpenImageIO 2.4 does not
//          read BC1 behind a DX10 header),
//   BC4 -> FourCC 'ATI1' (the legacy code every BC4-capable reader knows;
//          OpenImageIO 2.4 reads it as one channel).
// Read: those, plus 'BC4U' and the DX10 extended header with
// DXGI_FORMAT_BC1_UNORM (71) or DXGI_FORMAT_BC4_UNORM (80), so files from
// other tools load too. Width and height need not be multiples of 4: the
// blocks cover ceil(w/4) x ceil(h/4), row-major, as block_image.h lays them.
// Writes go through AtomicFile (temp file + rename).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "base/error.h"

namespace bounce {

class DdsError : public Error {
 public:
  using Error::Error;
};

enum class DdsFormat { kBc1, kBc4 };

struct DdsImage {
  DdsFormat format = DdsFormat::kBc1;
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> blocks;  // top mip level only
};

// Bytes of blocks of a width x height image (8 per 4x4 block for both formats).
std::size_t dds_block_bytes(std::uint32_t width, std::uint32_t height);

// Throws DdsError (naming the file) if the block count does not match the
// size, and IoError if the file cannot be written.
void write_dds(const std::filesystem::path& path, DdsFormat format, std::uint32_t width,
               std::uint32_t height, std::span<const std::uint8_t> blocks);

// Throws DdsError naming the file: cannot open, bad magic, truncated header
// or data, corrupt header, unsupported format (anything but BC1 / BC4, cube
// maps, volumes, texture arrays).
DdsImage read_dds(const std::filesystem::path& path);

}  // namespace bounce
