// Inputs that fuzzing (tests/fuzz, ./dev.sh fuzz) found to crash, hang or
// leak, kept in tests/fuzz/regressions/ and loaded here the way the CLI loads
// a bare mesh file. Each must end in one LoadError naming the file, with the
// reason the fix gives; under ./dev.sh sanitize this also runs with ASan.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

#include "expect_load_error.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

const fs::path kRegressions =
    fs::path(BOUNCE_RESOURCE_DIR) / ".." / "tests" / "fuzz" / "regressions";

struct Regression {
  const char* file;
  const char* reason;  // expected in the error message
};

// Each input, what Assimp 5.2 did with it, and what refuses it now. The PLY
// header check (core/scene/ply_check) reads a PLY header before Assimp does
// and accepts only the keywords the format has, so the damaged header lines
// of the first three now stop there.
const Regression kKnownInputs[] = {
    // Binary PLY, a damaged property line and no end_header: Assimp read past
    // its buffer (SEGV).
    {"ply-header-without-end-header.ply", "malformed PLY: unknown header keyword 'pro?"},
    // Assimp leaked an aiMesh on this malformed OBJ (suppressed, third-party);
    // the loader still refuses it with Assimp's message.
    {"obj-assimp-leaks-on-error.obj", "Assimp"},
    // A damaged property line ("propertyal oft ny") shifted the binary layout
    // so that face 0 had no indices: Assimp's Triangulate aborted the process
    // (ai_assert). The mesh import also refuses index-less faces itself.
    {"ply-face-without-indices.ply", "malformed PLY: unknown header keyword 'propertyal'"},
    // Damaged 'property' lines ("propert999...9y float x"): Assimp corrupted
    // its heap on them (ASan: a freed chunk in the wrong state, found by CI's
    // fuzz campaign).
    {"ply-unknown-header-keyword.ply", "malformed PLY: unknown header keyword 'propert9999"},
    // "end_header", a vertical tab, then the ascii body on the same line:
    // Assimp worked on it for more than 10 s (libFuzzer timeout).
    {"ply-end-header-followed-by-vertical-tab.ply",
     "malformed PLY: the 'end_header' line has more on it"},
    // Ascii, "element face 244444444444" in a 335-byte file: Assimp
    // allocated for the declared count first (ASan: out of memory, 63 GB).
    // More than Assimp's unsigned int can count; a smaller count would be
    // refused where the body runs out (test_ply_check.cpp).
    {"ply-ascii-face-count-beyond-the-file.ply",
     "malformed PLY: element 'face' declares 244444444444 items on line 11, more than"},
    // Ascii, "element 9999999999999face 6" (found by CI's campaign): Assimp
    // read the count from the element's name, 9999999999999 wrapped to 32
    // bits, and asked for 31 GB. Elements Assimp cannot read are refused, and
    // every element and list count must be backed by values in the body.
    {"ply-ascii-out-of-memory-in-assimp.ply",
     "malformed PLY: element '9999999999999face' on line 11 is not one the PLY reader"},
    // glTF with a damaged attribute name ("POSITs", found by a longer
    // campaign on a kept work corpus): a line strip without vertices, of
    // which Assimp made 2^32 - 1 lines (ASan: out of memory, 64 GB). A byte
    // that is not UTF-8 in another key stops it now at the glTF check
    // (core/scene/gltf_check); without that byte, the missing POSITION would
    // (test_gltf_check.cpp).
    {"gltf-line-strip-without-positions.gltf", "malformed glTF: not valid UTF-8 JSON"},
    // glTF with an embedded image whose data URI names the media type
    // "ima<amfng" (a longer campaign): Assimp read past a '/' that is not
    // there (SIGSEGV in the release build too).
    {"gltf-image-media-type-without-slash.gltf",
     "malformed glTF: images[0]'s media type 'ima<amfng' is not a type/subtype"},
    // glTF starting {"nodesasset": 44E1357 (a campaign on the glTF check
    // itself): the JSON parser threw its out-of-range error, not a parse
    // error, past the check's handler, and the process ended.
    {"gltf-number-beyond-double-range.gltf", "number overflow parsing '44E1357'"},
};

class FuzzRegression : public ::testing::TestWithParam<Regression> {};

TEST_P(FuzzRegression, IsOneLoadErrorNamingTheFile) {
  const fs::path file = kRegressions / GetParam().file;
  ASSERT_TRUE(fs::is_regular_file(file)) << file;
  test::expect_load_error(file, GetParam().reason);
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
