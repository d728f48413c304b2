// .npy round trips, errors on wrong dtype and truncation, atomic folders.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/atomic_file.h"
#include "io/npy.h"
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
