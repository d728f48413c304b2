// DDS files of BC1 / BC4 blocks: round trips, OpenImageIO opens them and
// decodes the same pixels as our decoders, clear errors on bad files.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "block_bench.h"
#include "compress/block_bc1.h"
#include "compress/block_bc4.h"
#include "compress/block_image.h"
#include "compress/dds.h"
#include "error_text.h"
#include "memory_cap.h"
#include "scratch_dir.h"

namespace bounce {

namespace fs = std::filesystem;

namespace {

class DdsTest : public ::testing::Test {
 protected:
  test::ScratchDir scratch{"bounce-dds"};
  const fs::path dir = scratch.path();
};

// Random blocks: both BC1 modes (c0 > c1 and c0 <= c1) and both BC4 modes
// occur, so every decoder path is compared.
std::vector<std::uint8_t> random_blocks(std::size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<std::uint8_t> blocks(count * 8);
  for (auto& b : blocks) b = static_cast<std::uint8_t>(rng());
  return blocks;
}

struct OiioPixels {
  int width = 0, height = 0, channels = 0;
  std::string compression;
  std::vector<std::uint8_t> pixels;
};

OiioPixels read_with_oiio(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    ADD_FAILURE() << "OpenImageIO cannot open " << path << ": " << OIIO::geterror();
    return {};
  }
  const OIIO::ImageSpec& spec = in->spec();
  OiioPixels out{
      spec.width, spec.height, spec.nchannels, spec.get_string_attribute("compression"), {}};
  out.pixels.resize(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, out.pixels.data()))
      << in->geterror();
  return out;
}

// Our decoders on blocks covering ceil(w/4) x ceil(h/4), cropped to w x h.
std::vector<std::uint8_t> decode_cropped(DdsFormat format, std::uint32_t w, std::uint32_t h,
                                         const std::vector<std::uint8_t>& blocks) {
  const std::size_t pw = (w + 3) / 4 * 4, ph = (h + 3) / 4 * 4;
  const int channels = format == DdsFormat::kBc1 ? 3 : 1;
  const std::vector<std::uint8_t> full = format == DdsFormat::kBc1
                                             ? decode_bc1_image(pw, ph, blocks)
                                             : decode_bc4_image(pw, ph, blocks);
  std::vector<std::uint8_t> out;
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) out.push_back(full[(y * pw + x) * channels + c]);
  return out;
}

// BC1 transparent black: three-colour mode (c0 <= c1) and index 3.
bool transparent(const std::vector<std::uint8_t>& blocks, std::uint32_t w, std::size_t x,
                 std::size_t y) {
  const std::uint8_t* b = &blocks[((y / 4) * ((w + 3) / 4) + x / 4) * 8];
  const int c0 = b[0] | b[1] << 8, c1 = b[2] | b[3] << 8;
  const int index = (b[4 + y % 4] >> (2 * (x % 4))) & 3;
  return c0 <= c1 && index == 3;
}

void write_bytes(const fs::path& path, const std::vector<char>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::vector<char> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void expect_error(const fs::path& path, const std::string& words) {
  try {
    read_dds(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const DdsError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    EXPECT_NE(what.find(words), std::string::npos) << what;
  }
}

}  // namespace

TEST_F(DdsTest, Bc1RoundTripAndOpenImageIOAgreesWithOurDecoder) {
  // An encoded image (realistic content) and random blocks (both modes).
  for (const auto& [w, h] : {std::pair<std::uint32_t, std::uint32_t>{16, 12}, {10, 6}}) {
    const std::size_t blocks_count = ((w + 3) / 4) * ((h + 3) / 4);
    std::vector<std::uint8_t> blocks = random_blocks(blocks_count, w);
    const BlockBenchData data = make_block_bench_data(16);  // codes of a smooth matrix
    const auto encoded = encode_bc1_image(16, 16, data.rgb, data.weights, Bc1Encoder::kWeighted);
    std::copy(encoded.begin(), encoded.begin() + 16, blocks.begin());  // two real blocks
    const fs::path path = dir / ("m" + std::to_string(w) + ".dds");
    write_dds(path, DdsFormat::kBc1, w, h, blocks);
    EXPECT_EQ(fs::file_size(path), 128 + blocks.size());

    const DdsImage back = read_dds(path);
    EXPECT_EQ(back.format, DdsFormat::kBc1);
    EXPECT_EQ(back.width, w);
    EXPECT_EQ(back.height, h);
    EXPECT_EQ(back.blocks, blocks);

    const OiioPixels oiio = read_with_oiio(path);
    EXPECT_EQ(oiio.width, static_cast<int>(w));
    EXPECT_EQ(oiio.height, static_cast<int>(h));
    EXPECT_EQ(oiio.compression, "DXT1");
    ASSERT_EQ(oiio.channels, 4);  // OpenImageIO reads DXT1 as RGBA
    const auto ours = decode_cropped(DdsFormat::kBc1, w, h, blocks);
    // OpenImageIO 2.4 decodes with bcdec, which rounds where libsquish (and
    // so our decoder) truncates or replicates bits: endpoints are
    // round(q 255/31) instead of (q << 3 | q >> 2), and the 1/3, 2/3 and 1/2
    // points are rounded from the 5/6-bit values instead of truncated from
    // the 8-bit ones. Exhaustively over all endpoint pairs the two differ by
    // at most one code, and GPUs differ among themselves likewise (the D3D
    // spec allows it). Alpha is 0 exactly on transparent black.
    int max_diff = 0, differing = 0;
    for (std::size_t y = 0; y < h; ++y)
      for (std::size_t x = 0; x < w; ++x) {
        const std::size_t k = y * w + x;
        for (int c = 0; c < 3; ++c) {
          const int d = std::abs(oiio.pixels[k * 4 + c] - ours[k * 3 + c]);
          max_diff = std::max(max_diff, d);
          differing += d != 0;
        }
        EXPECT_EQ(oiio.pixels[k * 4 + 3], transparent(blocks, w, x, y) ? 0 : 255);
      }
    EXPECT_LE(max_diff, 1);
    std::printf("BC1 %ux%u: %d of %u values differ by 1 between OpenImageIO and ours\n", w, h,
                differing, 3 * w * h);
  }
}

TEST_F(DdsTest, Bc4RoundTripAndOpenImageIOAgreesWithOurDecoder) {
  const std::uint32_t w = 12, h = 8;
  const std::vector<std::uint8_t> blocks = random_blocks(6, 99);
  const fs::path path = dir / "grey.dds";
  write_dds(path, DdsFormat::kBc4, w, h, blocks);
  const DdsImage back = read_dds(path);
  EXPECT_EQ(back.format, DdsFormat::kBc4);
  EXPECT_EQ(back.blocks, blocks);

  const OiioPixels oiio = read_with_oiio(path);
  EXPECT_EQ(oiio.width, static_cast<int>(w));
  EXPECT_EQ(oiio.height, static_cast<int>(h));
  EXPECT_EQ(oiio.compression, "BC4");
  ASSERT_EQ(oiio.channels, 1);
  const auto ours = decode_cropped(DdsFormat::kBc4, w, h, blocks);
  // Our BC4 decoder truncates the interpolation as libsquish does;
  // OpenImageIO 2.4 (bcdec) adds 1 before dividing by 7 or 5: at most one
  // code apart (checked exhaustively over all endpoint pairs).
  int max_diff = 0, differing = 0;
  for (std::size_t k = 0; k < ours.size(); ++k) {
    const int d = std::abs(oiio.pixels[k] - ours[k]);
    max_diff = std::max(max_diff, d);
    differing += d != 0;
  }
  EXPECT_LE(max_diff, 1);
  std::printf("BC4: %d of %zu values differ by 1 between OpenImageIO and ours\n", differing,
              ours.size());
}

TEST_F(DdsTest, ReadsDx10HeadersOfOtherTools) {
  const std::vector<std::uint8_t> blocks = random_blocks(4, 5);
  for (const auto& [dxgi, format] :
       {std::pair<std::uint32_t, DdsFormat>{71, DdsFormat::kBc1}, {80, DdsFormat::kBc4}}) {
    const fs::path path = dir / "dx10.dds";
    write_dds(path, DdsFormat::kBc1, 8, 8, blocks);
    std::vector<char> bytes = read_bytes(path);
    const char dx10[4] = {'D', 'X', '1', '0'};
    std::copy(dx10, dx10 + 4, bytes.begin() + 84);  // pixel format FourCC
    std::vector<char> ext(20, 0);
    ext[0] = static_cast<char>(dxgi);
    ext[4] = 3;   // TEXTURE2D
    ext[12] = 1;  // array size
    bytes.insert(bytes.begin() + 128, ext.begin(), ext.end());
    write_bytes(path, bytes);
    const DdsImage image = read_dds(path);
    EXPECT_EQ(image.format, format);
    EXPECT_EQ(image.blocks, blocks);
  }
}

TEST_F(DdsTest, BadFilesAreErrorsNamingTheFile) {
  const std::vector<std::uint8_t> blocks = random_blocks(4, 6);
  const fs::path good = dir / "good.dds";
  write_dds(good, DdsFormat::kBc1, 8, 8, blocks);
  const std::vector<char> bytes = read_bytes(good);

  expect_error(dir / "missing.dds", "cannot open");

  std::vector<char> bad = bytes;
  bad[0] = 'P';
  write_bytes(dir / "magic.dds", bad);
  expect_error(dir / "magic.dds", "bad magic");

  write_bytes(dir / "short.dds", std::vector<char>(bytes.begin(), bytes.begin() + 60));
  expect_error(dir / "short.dds", "truncated");

  write_bytes(dir / "cut.dds", std::vector<char>(bytes.begin(), bytes.end() - 5));
  expect_error(dir / "cut.dds", "truncated");

  bad = bytes;
  const char dxt5[4] = {'D', 'X', 'T', '5'};
  std::copy(dxt5, dxt5 + 4, bad.begin() + 84);
  write_bytes(dir / "dxt5.dds", bad);
  expect_error(dir / "dxt5.dds", "unsupported format: FourCC 'DXT5'");

  bad = bytes;
  bad[80] = 0x40;  // DDPF_RGB instead of DDPF_FOURCC
  write_bytes(dir / "rgb.dds", bad);
  expect_error(dir / "rgb.dds", "unsupported format");

  bad = bytes;
  bad[4] = 100;  // header size field
  write_bytes(dir / "corrupt.dds", bad);
  expect_error(dir / "corrupt.dds", "corrupt header");

  // Writing checks the block count and leaves no file behind on error.
  EXPECT_THROW(write_dds(dir / "wrong.dds", DdsFormat::kBc4, 8, 8, random_blocks(3, 1)), DdsError);
  EXPECT_FALSE(fs::exists(dir / "wrong.dds"));
  EXPECT_THROW(write_dds(dir / "empty.dds", DdsFormat::kBc1, 0, 4, {}), DdsError);
}

// A valid 8x8 DXT1 file with its header's width and height replaced.
std::vector<char> with_size(const std::vector<char>& good, std::uint32_t width,
                            std::uint32_t height) {
  std::vector<char> bytes = good;
  for (int k = 0; k < 4; ++k) {
    bytes[12 + static_cast<std::size_t>(k)] = static_cast<char>((height >> (8 * k)) & 0xff);
    bytes[16 + static_cast<std::size_t>(k)] = static_cast<char>((width >> (8 * k)) & 0xff);
  }
  return bytes;
}

// The error read_dds gives for `path`, or "" when it reads the file.
std::string dds_error(const fs::path& path) {
  return test::error_text<DdsError>([&] { read_dds(path); });
}

TEST_F(DdsTest, HugeSizeInAHeaderIsRefusedBeforeAllocating) {
  write_dds(dir / "good.dds", DdsFormat::kBc1, 8, 8, random_blocks(4, 7));
  const std::vector<char> good = read_bytes(dir / "good.dds");
  // 65536 x 65536 asks for 2 GiB of blocks, 2^32 - 1 squared for 2^63 bytes
  // (more than a std::vector may hold); the file has 32.
  write_bytes(dir / "2gib.dds", with_size(good, 65536, 65536));
  const std::string answer = test::with_memory_cap([&] { return dds_error(dir / "2gib.dds"); });
  EXPECT_NE(answer.find("2gib.dds: truncated: header width x height 65536x65536 needs "
                        "2147483648 bytes of blocks, found 32"),
            std::string::npos)
      << answer;
  write_bytes(dir / "max.dds", with_size(good, 0xffffffffu, 0xffffffffu));
  const std::string max = test::with_memory_cap([&] { return dds_error(dir / "max.dds"); });
  EXPECT_NE(max.find("max.dds: truncated: header width x height 4294967295x4294967295 needs "
                     "9223372036854775808 bytes"),
            std::string::npos)
      << max;
}

TEST_F(DdsTest, FolderOrDeviceInPlaceOfAFileIsRefused) {
  fs::create_directories(dir / "folder.dds");
  EXPECT_NE(dds_error(dir / "folder.dds").find("not a regular file"), std::string::npos);
  fs::create_symlink("/dev/zero", dir / "zero.dds");
  EXPECT_NE(dds_error(dir / "zero.dds").find("not a regular file"), std::string::npos);
}

}  // namespace bounce
