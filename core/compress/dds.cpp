#include "compress/dds.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>

#include "base/checked_size.h"
#include "io/atomic_file.h"

namespace bounce {

namespace {

// Field values from Microsoft's DDS reference (DDS_HEADER, DDS_PIXELFORMAT,
// DDS_HEADER_DXT10).
constexpr std::uint32_t kMagic = 0x20534444;  // "DDS "
constexpr std::uint32_t kHeaderSize = 124, kPixelFormatSize = 32;
constexpr std::uint32_t kFlagCaps = 0x1, kFlagHeight = 0x2, kFlagWidth = 0x4,
                        kFlagPixelFormat = 0x1000, kFlagMipMapCount = 0x20000,
                        kFlagLinearSize = 0x80000;
constexpr std::uint32_t kPixelFourCC = 0x4;
constexpr std::uint32_t kCapsTexture = 0x1000;
constexpr std::uint32_t kCaps2CubeMap = 0x200, kCaps2Volume = 0x200000;
constexpr std::uint32_t kDxgiBc1Unorm = 71, kDxgiBc4Unorm = 80;
constexpr std::uint32_t kDimensionTexture2D = 3;

constexpr std::uint32_t fourcc(const char (&s)[5]) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(s[0])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[1])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[2])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[3])) << 24;
}

// 32-bit words of the header, little-endian whatever the host.
void put32(std::uint8_t* at, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) at[k] = static_cast<std::uint8_t>(v >> (8 * k));
}
std::uint32_t get32(const std::uint8_t* at) {
  return static_cast<std::uint32_t>(at[0]) | static_cast<std::uint32_t>(at[1]) << 8 |
         static_cast<std::uint32_t>(at[2]) << 16 | static_cast<std::uint32_t>(at[3]) << 24;
}

std::string fourcc_text(std::uint32_t v) {
  std::string s;
  for (int k = 0; k < 4; ++k) {
    const auto ch = static_cast<char>((v >> (8 * k)) & 0xff);
    s += (ch >= 32 && ch < 127) ? ch : '?';
  }
  return s;
}

// Word offsets inside the 128 bytes that start with the magic.
enum Word : int {
  kWordMagic = 0,
  kWordSize = 1,
  kWordFlags = 2,
  kWordHeight = 3,
  kWordWidth = 4,
  kWordLinearSize = 5,
  kWordDepth = 6,
  kWordMipMapCount = 7,
  kWordPfSize = 19,
  kWordPfFlags = 20,
  kWordPfFourCC = 21,
  kWordCaps = 27,
  kWordCaps2 = 28,
};
constexpr std::size_t kFileHeaderBytes = 128, kDx10Bytes = 20;

}  // namespace

std::size_t dds_block_bytes(std::uint32_t width, std::uint32_t height) {
  return ((static_cast<std::size_t>(width) + 3) / 4) *
         ((static_cast<std::size_t>(height) + 3) / 4) * 8;
}

void write_dds(const std::filesystem::path& path, DdsFormat format, std::uint32_t width,
               std::uint32_t height, std::span<const std::uint8_t> blocks) {
  if (width == 0 || height == 0)
    throw DdsError(path.string(), "cannot write an empty image (" + std::to_string(width) + "x" +
                                      std::to_string(height) + ")");
  const std::size_t bytes = dds_block_bytes(width, height);
  if (blocks.size() != bytes)
    throw DdsError(path.string(), "a " + std::to_string(width) + "x" + std::to_string(height) +
                                      " image needs " + std::to_string(bytes) +
                                      " bytes of blocks, got " + std::to_string(blocks.size()));
  std::uint8_t header[kFileHeaderBytes] = {};
  auto word = [&](int w, std::uint32_t v) { put32(header + 4 * w, v); };
  word(kWordMagic, kMagic);
  word(kWordSize, kHeaderSize);
  word(kWordFlags, kFlagCaps | kFlagHeight | kFlagWidth | kFlagPixelFormat | kFlagMipMapCount |
                       kFlagLinearSize);
  word(kWordHeight, height);
  word(kWordWidth, width);
  // The field is 32 bits; beyond 4 GiB write 0 (readers compute the size
  // from width and height anyway, and so does read_dds).
  word(kWordLinearSize,
       bytes <= std::numeric_limits<std::uint32_t>::max() ? static_cast<std::uint32_t>(bytes) : 0u);
  word(kWordMipMapCount, 1);
  word(kWordPfSize, kPixelFormatSize);
  word(kWordPfFlags, kPixelFourCC);
  word(kWordPfFourCC, format == DdsFormat::kBc1 ? fourcc("DXT1") : fourcc("ATI1"));
  word(kWordCaps, kCapsTexture);
  AtomicFile file(path);
  file.stream().write(reinterpret_cast<const char*>(header), sizeof header);
  file.stream().write(reinterpret_cast<const char*>(blocks.data()),
                      static_cast<std::streamsize>(blocks.size()));
  file.commit();
}

DdsImage read_dds(const std::filesystem::path& path) {
  const std::string where = path.string();
  // The header's width and height are compared with the file's real size
  // before the blocks are allocated: a 128-byte file must not be able to
  // ask for gigabytes.
  const std::size_t file_size = regular_file_size<DdsError>(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DdsError(where, std::string("cannot open: ") + std::strerror(errno));
  std::uint8_t header[kFileHeaderBytes + kDx10Bytes];
  in.read(reinterpret_cast<char*>(header), kFileHeaderBytes);
  const auto got = static_cast<std::size_t>(in.gcount());
  if (got >= 4 && get32(header) != kMagic)
    throw DdsError(where, "not a DDS file (bad magic, expected \"DDS \")");
  if (got < kFileHeaderBytes)
    throw DdsError(where, "truncated: " + std::to_string(got) + " bytes, a DDS header needs 128");
  auto word = [&](int w) { return get32(header + 4 * w); };
  if (word(kWordSize) != kHeaderSize || word(kWordPfSize) != kPixelFormatSize)
    throw DdsError(where, "corrupt header (structure sizes " + std::to_string(word(kWordSize)) +
                              " and " + std::to_string(word(kWordPfSize)) +
                              ", expected 124 and 32)");
  DdsImage image;
  image.width = word(kWordWidth);
  image.height = word(kWordHeight);
  if (image.width == 0 || image.height == 0)
    throw DdsError(where, "corrupt header (size " + std::to_string(image.width) + "x" +
                              std::to_string(image.height) + ")");
  if (word(kWordCaps2) & (kCaps2CubeMap | kCaps2Volume))
    throw DdsError(where, "unsupported format: cube map or volume texture (only 2D BC1/BC4)");
  if (!(word(kWordPfFlags) & kPixelFourCC))
    throw DdsError(where, "unsupported format: uncompressed pixels (only BC1/DXT1 and BC4)");
  const std::uint32_t code = word(kWordPfFourCC);
  if (code == fourcc("DXT1")) {
    image.format = DdsFormat::kBc1;
  } else if (code == fourcc("ATI1") || code == fourcc("BC4U")) {
    image.format = DdsFormat::kBc4;
  } else if (code == fourcc("DX10")) {
    std::uint8_t* dx10 = header + kFileHeaderBytes;
    in.read(reinterpret_cast<char*>(dx10), kDx10Bytes);
    if (static_cast<std::size_t>(in.gcount()) < kDx10Bytes)
      throw DdsError(where, "truncated: the DX10 header extension is incomplete");
    const std::uint32_t dxgi = get32(dx10), dimension = get32(dx10 + 4),
                        array_size = get32(dx10 + 12);
    if (dxgi == kDxgiBc1Unorm) {
      image.format = DdsFormat::kBc1;
    } else if (dxgi == kDxgiBc4Unorm) {
      image.format = DdsFormat::kBc4;
    } else {
      throw DdsError(where, "unsupported format: DXGI format " + std::to_string(dxgi) +
                                " (only BC1_UNORM = 71 and BC4_UNORM = 80)");
    }
    if (dimension != kDimensionTexture2D || array_size > 1)
      throw DdsError(where, "unsupported format: not a single 2D texture (dimension " +
                                std::to_string(dimension) + ", array size " +
                                std::to_string(array_size) + ")");
  } else {
    throw DdsError(where, "unsupported format: FourCC '" + fourcc_text(code) +
                              "' (only DXT1, ATI1/BC4U or DX10 with BC1/BC4)");
  }
  // At most 2^30 x 2^30 blocks of 8 bytes: the product fits in 64 bits.
  const std::size_t bytes = dds_block_bytes(image.width, image.height);
  const std::size_t header_bytes =
      kFileHeaderBytes + (code == fourcc("DX10") ? kDx10Bytes : std::size_t(0));
  const std::size_t data = file_size - std::min(file_size, header_bytes);
  if (data < bytes)
    throw DdsError(where, "truncated: header width x height " + std::to_string(image.width) + "x" +
                              std::to_string(image.height) + " needs " + std::to_string(bytes) +
                              " bytes of blocks, found " + std::to_string(data));
  image.blocks.resize(bytes);
  in.read(reinterpret_cast<char*>(image.blocks.data()), static_cast<std::streamsize>(bytes));
  if (static_cast<std::size_t>(in.gcount()) < bytes)
    throw DdsError(where, "read failed after " + std::to_string(in.gcount()) + " of " +
                              std::to_string(bytes) + " bytes of blocks");
  return image;
}

}  // namespace bounce
