// Memory-mapped matrix buffers (base/mapped_buffer.h): what is written reads
// back, the temporary file is gone from the folder at once and from the
// process's mappings when the matrix is freed, and a folder that cannot hold
// the file gives an error naming it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>

#include "bake/out_of_core.h"
#include "base/error.h"
#include "base/mapped_buffer.h"
#include "scratch_dir.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

using test::ScratchDir;

// Lines of /proc/self/maps naming a file in `dir`.
int mappings_in(const fs::path& dir) {
  std::ifstream maps("/proc/self/maps");
  int count = 0;
  for (std::string line; std::getline(maps, line);)
    if (line.find((dir / "bounce-matrix-").string()) != std::string::npos) ++count;
  return count;
}

TEST(MappedBuffer, WritesReadBackAndTheFileIsGoneWithTheMatrix) {
  ScratchDir dir;
  {
    const OutOfCoreScope scope(OutOfCorePolicy{dir.path()});
    MatrixValues m(300 * 300);
    EXPECT_TRUE(is_mapped_matrix(m.data()));
    EXPECT_GE(mapped_matrix_bytes(), m.size() * sizeof(float));
    std::iota(m.begin(), m.end(), 0.0f);
    // Written back to the file and dropped from memory, then read again.
    release_residency(m);
    for (std::size_t i = 0; i < m.size(); i += 997) ASSERT_EQ(m[i], static_cast<float>(i));
    // The file was unlinked when it was mapped: nothing in the folder, one
    // mapping of a deleted file in the process.
    EXPECT_TRUE(fs::is_empty(dir.path()));
    EXPECT_EQ(mappings_in(dir.path()), 1);
    // A copy under the policy is a second mapping with the same bytes.
    const MatrixValues copy = m;
    EXPECT_TRUE(is_mapped_matrix(copy.data()));
    EXPECT_TRUE(std::equal(copy.begin(), copy.end(), m.begin()));
    EXPECT_EQ(mappings_in(dir.path()), 2);
  }
  EXPECT_EQ(mappings_in(dir.path()), 0);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(MappedBuffer, WithoutAPolicyMatricesAreOnTheHeap) {
  ASSERT_FALSE(out_of_core_policy().has_value());
  MatrixValues m(64 * 64, 1.0f);
  EXPECT_FALSE(is_mapped_matrix(m.data()));
  release_residency(m);  // a no-op on the heap
  EXPECT_EQ(m[17], 1.0f);
}

TEST(MappedBuffer, SpillMovesAFinishedHeapMatrixToAFile) {
  ScratchDir dir;
  MatrixValues m(200 * 200);
  std::iota(m.begin(), m.end(), 1.0f);
  const MatrixValues expected = m;
  ASSERT_FALSE(is_mapped_matrix(m.data()));
  const MatrixValues mapped = spill_to_file(std::move(m), OutOfCorePolicy{dir.path()});
  EXPECT_TRUE(is_mapped_matrix(mapped.data()));
  EXPECT_TRUE(mapped == expected);
  EXPECT_FALSE(out_of_core_policy().has_value());  // the spill's scope ended with it
  EXPECT_EQ(mappings_in(dir.path()), 1);
}

TEST(MappedBuffer, ScopesNestAndRestoreThePreviousPolicy) {
  ScratchDir a, b;
  {
    const OutOfCoreScope outer(OutOfCorePolicy{a.path()});
    {
      const OutOfCoreScope inner(std::nullopt);
      EXPECT_FALSE(out_of_core_policy().has_value());
    }
    ASSERT_TRUE(out_of_core_policy().has_value());
    EXPECT_EQ(out_of_core_policy()->dir, a.path());
  }
  EXPECT_FALSE(out_of_core_policy().has_value());
}

TEST(MappedBuffer, AFolderThatCannotHoldTheFileIsNamedInTheError) {
  ScratchDir dir;
  const fs::path missing = dir.path() / "no-such-folder";
  const fs::path file = dir.path() / "a-file";
  std::ofstream(file) << "x";
  for (const fs::path& bad : {missing, file}) {
    const OutOfCoreScope scope(OutOfCorePolicy{bad});
    try {
      MatrixValues m(1000);
      ADD_FAILURE() << "allocated a mapped matrix in " << bad;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), bad.string());
      EXPECT_NE(std::string(e.what()).find("temporary matrix file"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(mappings_in(dir.path()), 0);
}

TEST(OutOfCoreDecision, AutoMapsWhenTheDenseMatricesExceedHalfTheMemory) {
  BakeSettings s;
  const std::size_t gib = std::size_t(1) << 30;
  // 6 n^2 floats: n = 32768 is 24 GiB, n = 8192 is 1.5 GiB.
  EXPECT_EQ(dense_footprint_bytes(32768), 24 * gib);
  EXPECT_TRUE(decide_out_of_core(s, 32768, 24 * gib).on);
  EXPECT_FALSE(decide_out_of_core(s, 8192, 24 * gib).on);
  EXPECT_FALSE(decide_out_of_core(s, 8192, 0).on);  // unknown memory: in memory
  s.out_of_core = OutOfCore::On;
  EXPECT_TRUE(decide_out_of_core(s, 10, 24 * gib).on);
  s.out_of_core = OutOfCore::Off;
  EXPECT_FALSE(decide_out_of_core(s, 32768, 24 * gib).on);
  s.out_of_core = OutOfCore::On;
  s.out_of_core_dir = "/some/where";
  EXPECT_EQ(decide_out_of_core(s, 10, gib).dir, fs::path("/some/where"));
}

}  // namespace
}  // namespace bounce
