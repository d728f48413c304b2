// .npy round trips, errors on wrong dtype and truncation, atomic folders.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "../common/raw_npy.h"
#include "error_text.h"
#include "io/atomic_file.h"
#include "io/npy.h"
#include "memory_cap.h"
#include "scratch_dir.h"

namespace bounce {

namespace fs = std::filesystem;

class NpyTest : public ::testing::Test {
 protected:
  test::ScratchDir scratch{"bounce-npy"};
  const fs::path dir = scratch.path();
};

TEST_F(NpyTest, FloatRoundTripAndHeaderAlignment) {
  std::vector<float> v = {1.5f, -2.0f, 3.25f, 0.0f, 1e-30f, 7.0f};
  write_npy(dir / "a.npy", v, {2, 3});
  const auto a = read_npy_f32(dir / "a.npy");
  EXPECT_EQ(a.shape, (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(a.data, v);
  // Data starts on a 64-byte boundary, as NumPy writes it.
  EXPECT_EQ((fs::file_size(dir / "a.npy") - v.size() * 4) % 64, 0u);
}

TEST_F(NpyTest, WrongDtypeAndTruncationAreErrorsNamingTheFile) {
  std::vector<std::uint32_t> v = {1, 2, 3, 4};
  write_npy(dir / "u.npy", v, {4});
  EXPECT_EQ(read_npy_u32(dir / "u.npy").data, v);
  try {
    read_npy_f32(dir / "u.npy");
    FAIL();
  } catch (const NpyError& e) {
    EXPECT_NE(std::string(e.what()).find("u.npy"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("dtype"), std::string::npos);
  }
  fs::resize_file(dir / "u.npy", fs::file_size(dir / "u.npy") - 3);
  EXPECT_THROW(read_npy_u32(dir / "u.npy"), NpyError);
}

TEST_F(NpyTest, ShapeMismatchIsRefusedAndLeavesNoFile) {
  std::vector<float> v = {1, 2, 3};
  EXPECT_THROW(write_npy(dir / "bad.npy", v, {2, 2}), NpyError);
  EXPECT_FALSE(fs::exists(dir / "bad.npy"));
}

using test::write_raw_npy;

std::string f32_header(const std::string& shape) { return test::npy_header("<f4", shape); }

// The error read_npy_f32 gives for `path`, or "" when it reads the file.
std::string npy_error(const fs::path& path) {
  return test::error_text<NpyError>([&] { read_npy_f32(path); });
}

TEST_F(NpyTest, ShapeWhoseElementCountWrapsAroundIsRefused) {
  // 1773043451913644 x 3468 x 3 is 560 modulo 2^64: a file with 560 floats
  // would pass a size check made with the wrapped product, and the caller
  // would then believe the shape and allocate from it.
  const std::size_t a = 1773043451913644, b = 3468, c = 3;
  ASSERT_EQ(a * b * c, 560u);  // unsigned arithmetic wraps: that is the attack
  write_raw_npy(dir / "wrapped.npy", f32_header("(1773043451913644, 3468, 3)"), 560 * 4);
  const std::string what = npy_error(dir / "wrapped.npy");
  EXPECT_NE(what.find("wrapped.npy"), std::string::npos) << what;
  EXPECT_NE(what.find("'shape'"), std::string::npos) << what;
  EXPECT_NE(what.find("overflows"), std::string::npos) << what;
}

TEST_F(NpyTest, NegativeOrMalformedDimensionsAreRefused) {
  // "-1" would parse as 2^64 - 1; with a 0 beside it the element count is 0
  // and no size check could catch it.
  for (const std::string shape : {"(-1, 0)", "(3x, 2)", "(+2,)", "(18446744073709551616,)"}) {
    write_raw_npy(dir / "bad-shape.npy", f32_header(shape), 64);
    const std::string what = npy_error(dir / "bad-shape.npy");
    EXPECT_NE(what.find("'shape'"), std::string::npos) << shape << ": " << what;
  }
}

TEST_F(NpyTest, HeaderLengthBeyondTheFileIsRefusedBeforeAllocating) {
  // Version 2.0 has a 32-bit header length: almost 4 GiB from a 16-byte file.
  {
    std::ofstream out(dir / "long-header.npy", std::ios::binary);
    out.write("\x93NUMPY\x02\x00", 8);
    const std::uint32_t len = 0xfffffff0u;
    out.write(reinterpret_cast<const char*>(&len), 4);
    out << "{'de";
  }
  const std::string answer =
      test::with_memory_cap([&] { return npy_error(dir / "long-header.npy"); });
  EXPECT_NE(answer.find("long-header.npy"), std::string::npos) << answer;
  EXPECT_NE(answer.find("header length 4294967280"), std::string::npos) << answer;
}

TEST_F(NpyTest, ShapeBeyondTheFileIsRefusedBeforeAllocating) {
  write_raw_npy(dir / "big.npy", f32_header("(100000, 100000)"), 16);
  const std::string answer = test::with_memory_cap([&] { return npy_error(dir / "big.npy"); });
  EXPECT_NE(answer.find("big.npy: truncated: header field 'shape' (100000, 100000) needs "
                        "40000000000 bytes of data, file has 16"),
            std::string::npos)
      << answer;
}

TEST_F(NpyTest, EmptyArraysAndExactSizesStillRead) {
  write_raw_npy(dir / "empty.npy", f32_header("(0, 15)"), 0);
  EXPECT_EQ(read_npy_f32(dir / "empty.npy").shape, (std::vector<std::size_t>{0, 15}));
  write_raw_npy(dir / "exact.npy", f32_header("(2, 3)"), 24);
  EXPECT_EQ(read_npy_f32(dir / "exact.npy").data, std::vector<float>(6, 0.0f));
  write_raw_npy(dir / "short.npy", f32_header("(2, 3)"), 23);
  EXPECT_NE(npy_error(dir / "short.npy").find("truncated"), std::string::npos);
}

TEST_F(NpyTest, FolderOrDeviceInPlaceOfAFileIsRefused) {
  fs::create_directories(dir / "folder.npy");
  EXPECT_NE(npy_error(dir / "folder.npy").find("not a regular file"), std::string::npos);
  fs::create_symlink("/dev/zero", dir / "zero.npy");
  EXPECT_NE(npy_error(dir / "zero.npy").find("not a regular file"), std::string::npos);
  EXPECT_NE(npy_error(dir / "missing.npy").find("cannot open file"), std::string::npos);
}

TEST_F(NpyTest, AtomicDirectoryIsInvisibleUntilCommitted) {
  {
    AtomicDirectory d(dir / "bake");
    std::ofstream(d.path() / "x.txt") << "x";
    EXPECT_FALSE(fs::exists(dir / "bake"));
  }  // destroyed without commit: nothing left behind
  EXPECT_FALSE(fs::exists(dir / "bake"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 0);
  {
    AtomicDirectory d(dir / "bake");
    std::ofstream(d.path() / "manifest.json") << "{}";
    d.commit();
  }
  EXPECT_TRUE(fs::exists(dir / "bake" / "manifest.json"));
}

TEST_F(NpyTest, AtomicDirectoryRefusesToReplaceAFolderThatIsNotABake) {
  fs::create_directories(dir / "precious");
  std::ofstream(dir / "precious" / "thesis.tex") << "x";
  EXPECT_THROW(AtomicDirectory(dir / "precious"), IoError);
  EXPECT_TRUE(fs::exists(dir / "precious" / "thesis.tex"));
}

}  // namespace bounce
