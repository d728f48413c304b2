// The glTF check (core/scene/gltf_check) on the inputs fuzzing found Assimp
// 5.2 failing on: a mesh primitive without vertices (tens of gigabytes
// asked for) and an image media type without a '/' (a crash).
// Well-formed files, text and binary, still load.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "base/diagnostics.h"
#include "expect_load_error.h"
#include "scene/scene_loader.h"
#include "scratch_dir.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

// One triangle: three float vertices in a data URI (36 bytes).
const std::string kBuffer =
    R"("buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)"
    R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}])";

// The same in a binary file's own chunk: buffer 0 without a URI.
const std::string kBinaryBuffer =
    R"("buffers": [{"byteLength": 36}], "bufferViews": [{"buffer": 0, "byteLength": 36}])";

std::string gltf(const std::string& primitive, const std::string& count = "3",
                 const std::string& buffer = kBuffer) {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
 "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [)" +
         primitive + R"(]}],
 )" + buffer +
         R"(,
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": )" +
         count + R"(, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}]})";
}

class GltfCheck : public ::testing::Test {
 protected:
  test::ScratchDir scratch{"bounce-gltf"};
  const fs::path dir = scratch.path();

  fs::path write(const std::string& bytes, const char* name = "mesh.gltf") const {
    const fs::path p = dir / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }

  // Expects one LoadError about the file whose message holds `reason`.
  void expect_refused(const fs::path& file, const std::string& reason) {
    test::expect_load_error(file, reason);
  }

  std::size_t triangles(const fs::path& file) {
    Diagnostics diagnostics;
    return SceneLoader(diagnostics).load(file).triangle_count();
  }
};

std::string little_u32(std::uint32_t v) {
  std::string s(4, '\0');
  for (int i = 0; i < 4; ++i) s[static_cast<std::size_t>(i)] = static_cast<char>(v >> (8 * i));
  return s;
}

// The binary container as the format lays it out: a header, the JSON chunk
// padded with spaces to four bytes (declaring `declared_extra` bytes more
// than it holds), then a binary chunk with the triangle's three vertices.
std::string glb(std::string text, std::uint32_t declared_extra = 0) {
  while (text.size() % 4 != 0) text += ' ';
  std::string bin;
  for (const float f : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f}) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &f, 4);
    bin += little_u32(bits);
  }
  const auto chunk = static_cast<std::uint32_t>(text.size());
  const auto total = static_cast<std::uint32_t>(12 + 8 + chunk + 8 + bin.size());
  return "glTF" + little_u32(2) + little_u32(total) + little_u32(chunk + declared_extra) +
         little_u32(0x4E4F534Au) + text + little_u32(static_cast<std::uint32_t>(bin.size())) +
         little_u32(0x004E4942u) + bin;
}

TEST_F(GltfCheck, WellFormedTextAndBinaryFilesLoad) {
  const std::string text = gltf(R"({"attributes": {"POSITION": 0}})");
  EXPECT_EQ(triangles(write(text)), 1u);
  EXPECT_EQ(triangles(write(glb(gltf(R"({"attributes": {"POSITION": 0}})", "3", kBinaryBuffer)),
                            "mesh.glb")),
            1u);
}

TEST_F(GltfCheck, APrimitiveWithoutVerticesIsRefused) {
  // The fuzzed input's shape: a line strip whose attributes name no POSITION
  // (Assimp made 2^32 - 1 lines of it).
  expect_refused(write(gltf(R"({"attributes": {"POSITs": 0}, "mode": 3})")),
                 "mesh 0 primitive 0 has no POSITION attribute");
  expect_refused(write(gltf(R"({"attributes": {"POSITION": 1}})")),
                 "mesh 0 primitive 0's POSITION names no accessor of the 1");
  expect_refused(write(gltf(R"({"attributes": {"POSITION": 0}, "mode": 3})", "0")),
                 "POSITION accessor 0 holds no elements");
  expect_refused(write(gltf(R"({"attributes": {"POSITION": 0}, "indices": 7})")),
                 "primitive 0's indices names no accessor");
  expect_refused(write(glb(gltf(R"({"attributes": {"POSITs": 0}, "mode": 3})")), "mesh.glb"),
                 "has no POSITION attribute");
}

// The fuzzed input's shape: an embedded image whose data URI names the media
// type "ima<amfng". Assimp reads what follows the type's '/' without finding
// one first, and the process died (SIGSEGV) in `bounce info`.
TEST_F(GltfCheck, ImageMediaTypesWithoutASlashAreRefused) {
  const std::string text = gltf(R"({"attributes": {"POSITION": 0}})");
  const auto with_images = [&text](const std::string& images) {
    return text.substr(0, text.rfind('}')) + R"(, "images": )" + images + "}";
  };
  expect_refused(write(with_images(R"([{"uri": "data:image;base64,AAAA"}])")),
                 "images[0]'s media type 'image' is not a type/subtype");
  expect_refused(write(with_images(R"([{"uri": "data:image/png;base64,AAAA"},
                                       {"bufferView": 0, "mimeType": "x"}])")),
                 "images[1]'s media type 'x'");
  expect_refused(write(with_images(R"([{"bufferView": 0, "mimeType": 5}])")),
                 "images[0]'s mimeType is not text");
}

TEST_F(GltfCheck, JsonThatIsNotUtf8OrCutShortIsRefused) {
  std::string text = gltf(R"({"attributes": {"POSITION": 0}})");
  text.replace(text.find("componentType"), 1, "\xf4");
  expect_refused(write(text), "malformed glTF: not valid UTF-8 JSON");
  expect_refused(write(glb(gltf(R"({"attributes": {"POSITION": 0}})"), 1000), "mesh.glb"),
                 "the JSON chunk declares");
  expect_refused(write("glTF\x02\0\0\0", "mesh.glb"), "cut short");
  // A number beyond a double's range (fuzzing: the parser threw something
  // other than a parse error, which ended the process).
  expect_refused(write(R"({"asset": 44E1357})"), "malformed glTF: not valid UTF-8 JSON");
}

}  // namespace
}  // namespace bounce
