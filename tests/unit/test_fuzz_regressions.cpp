// Inputs that fuzzing (tests/fuzz, ./dev.sh fuzz) found to crash, hang or
// leak, kept in tests/fuzz/regressions/ and loaded here the way the CLI loads
// a bare mesh file. Each must end in one LoadError naming the file, with the
// reason the fix gives; under ./dev.sh sanitize this also runs with ASan.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

#include "base/diagnostics.h"
#include "scene/scene_loader.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

const fs::path kRegressions =
    fs::path(BOUNCE_RESOURCE_DIR) / ".." / "tests" / "fuzz" / "regressions";

struct Regression {
  const char* file;
  const char* reason;  // expected in the error message
};

// Assimp 5.2 read past its buffer (SEGV) on a binary PLY whose header has no
// end_header; the PLY structure check refuses it first.
// Assimp leaked an aiMesh on this malformed OBJ (suppressed, third-party);
// the loader still refuses it with Assimp's message.
const Regression kKnownInputs[] = {
    {"ply-header-without-end-header.ply", "malformed PLY: the header has no 'end_header' line"},
    {"obj-assimp-leaks-on-error.obj", "Assimp"},
    // A face list whose first face has no indices: Assimp's Triangulate
    // aborted the process (ai_assert) on it.
    {"ply-face-without-indices.ply", "corrupt file: face 0 of mesh 0 has no vertex indices"},
};

class FuzzRegression : public ::testing::TestWithParam<Regression> {};

TEST_P(FuzzRegression, IsOneLoadErrorNamingTheFile) {
  const fs::path file = kRegressions / GetParam().file;
  ASSERT_TRUE(fs::is_regular_file(file)) << file;
  Diagnostics diagnostics;
  try {
    (void)SceneLoader(diagnostics).load(file);
    ADD_FAILURE() << "loaded " << file << " without an error";
  } catch (const SceneLoader::LoadError& e) {
    EXPECT_EQ(e.where(), file.string());
    EXPECT_NE(std::string(e.what()).find(GetParam().reason), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Inputs, FuzzRegression, ::testing::ValuesIn(kKnownInputs),
                         [](const auto& param_info) {
                           std::string name = param_info.param.file;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace bounce
