// The PLY check (core/scene/ply_check) on the classes of input fuzzing found
// Assimp 5.2 allocating gigabytes for: every count Assimp reads before it
// reads the data (element counts, list counts, counts hidden in element
// names) must be backed by values in the file. Well-formed files in
// the variants the check has to follow (CR LF, tabs, both endians) still load.
#include <gtest/gtest.h>

#include <cstdint>
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

class PlyCheck : public ::testing::Test {
 protected:
  test::ScratchDir scratch{"bounce-ply"};
  const fs::path dir = scratch.path();

  fs::path write(const std::string& text) const {
    const fs::path p = dir / "mesh.ply";
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

  // Expects one LoadError about the file whose message holds `reason`.
  void expect_refused(const std::string& text, const std::string& reason) {
    test::expect_load_error(write(text), reason);
  }

  std::size_t triangles(const std::string& text) {
    Diagnostics diagnostics;
    return SceneLoader(diagnostics).load(write(text)).triangle_count();
  }
};

// A unit quad: 4 vertices, one quad face (two triangles once triangulated).
std::string header(const std::string& format, const std::string& face_count = "1") {
  return "ply\nformat " + format +
         " 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty "
         "float z\n"
         "element face " +
         face_count + "\nproperty list uchar int vertex_indices\nend_header\n";
}
const std::string kVertices = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";

std::string little_endian_body(std::uint8_t list_count_byte) {
  std::string body;
  const float v[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  body.append(reinterpret_cast<const char*>(v), sizeof v);
  body.push_back(static_cast<char>(list_count_byte));
  const std::int32_t idx[4] = {0, 1, 2, 3};
  body.append(reinterpret_cast<const char*>(idx), sizeof idx);
  return body;
}

TEST_F(PlyCheck, WellFormedVariantsLoad) {
  EXPECT_EQ(triangles(header("ascii") + kVertices + "4 0 1 2 3\n"), 2u);
  // Tabs and runs of spaces, exponents and signs.
  EXPECT_EQ(triangles(header("ascii") + "0 0 0\n1e0\t0  -0\n+1.0 1.000 0\n0 1 0.0e+0\n4 0 1 2 3\n"),
            2u);
  // CR LF everywhere.
  std::string crlf;
  for (const char c : header("ascii") + kVertices + "4 0 1 2 3\n") {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  EXPECT_EQ(triangles(crlf), 2u);
  EXPECT_EQ(triangles(header("binary_little_endian") + little_endian_body(4)), 2u);
}

TEST_F(PlyCheck, AsciiListCountBeyondItsLineIsRefused) {
  // Assimp resizes the list to the count before reading it: 4e9 * 8 bytes.
  expect_refused(header("ascii") + kVertices + "4000000000 0 1 2 3\n",
                 "element 'face' item 0 of 1 on line 14 has a list count of "
                 "4000000000 but 4");
  // One more value than the count: the item is not one line of its values.
  expect_refused(header("ascii") + kVertices + "3 0 1 2 3\n",
                 "has 5 values, its properties take 4");
}

TEST_F(PlyCheck, AsciiDataWithoutAFinalLineEndIsRefused) {
  // Assimp read this last line as "4 0 1 2 30": leftovers of the longer line
  // before it. A count there could grow the same way.
  expect_refused(header("ascii") + "0 0 0\n1 0 0\n1 1 0\n0 1 0.0e+0\n4 0 1 2 3",
                 "the last line of the ascii data (line 14) has no line end");
}

TEST_F(PlyCheck, AsciiItemsBeyondTheFileAreRefused) {
  // Assimp sizes its face array by the header's count before reading.
  expect_refused(header("ascii", "1000000") + kVertices + "4 0 1 2 3\n",
                 "truncated: the file ends before element 'face' item 1 of 1000000 (the header "
                 "declares it on line 7)");
}

TEST_F(PlyCheck, NegativeListCountIsRefused) {
  // A signed count of -1 becomes 4294967295 in Assimp's unsigned int.
  const std::string signed_header =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty "
      "float y\n"
      "property float z\nelement face 1\nproperty list int int "
      "vertex_indices\nend_header\n";
  expect_refused(signed_header + kVertices + "-1 0 1 2\n", "list count of -1");
}

TEST_F(PlyCheck, BinaryListLongerThanTheFileIsRefused) {
  // The count byte says 255 indices (1020 bytes); the file holds 16.
  expect_refused(header("binary_little_endian") + little_endian_body(255),
                 "element 'face' item 0 of 1 has a list of 255 values, the file holds 16");
}

TEST_F(PlyCheck, BinaryItemsBeyondTheFileAreRefused) {
  expect_refused(header("binary_little_endian", "2") + little_endian_body(4),
                 "truncated: the file ends inside element 'face' item 1 of 2");
}

TEST_F(PlyCheck, CountHiddenInAnElementNameIsRefused) {
  // The CI fuzz input: Assimp read "99999999999999face 6" as 276447231 items.
  std::string text = header("ascii");
  text.replace(text.find("element face 1"), 14, "element 99999999999999face 6");
  expect_refused(text + kVertices + "4 0 1 2 3\n", "element '99999999999999face' on line 7 is not");
}

TEST_F(PlyCheck, AnElementDeclaredTwiceIsRefused) {
  // The fuzz input: a second, longer vertex element, which Assimp read into
  // the first one's array, past its end.
  std::string text = header("ascii");
  text.insert(text.find("end_header"), "element vertex 5\nproperty float x\n");
  expect_refused(text + kVertices + "4 0 1 2 3\n0\n0\n0\n0\n0\n",
                 "element 'vertex' is declared twice (lines 3 and 9)");
}

TEST_F(PlyCheck, CommentsAreNotCounted) {
  // Assimp 5.2.5 skips comment lines, numbers and element names in them too.
  for (const char* comment : {"comment 4000000000 points scanned\n", "comment vertex 7\n",
                              "comment made by hand, 4 vertices\n"}) {
    std::string text = header("ascii");
    text.insert(text.find("element vertex"), comment);
    EXPECT_EQ(triangles(text + kVertices + "4 0 1 2 3\n"), 2u) << comment;
  }
}

TEST_F(PlyCheck, ElementsAssimpCannotCountAreRefused) {
  // Assimp reads no count for "camera" and then reads the camera's line as
  // the first vertex.
  std::string text = header("ascii");
  text.insert(text.find("element vertex"), "element camera 1\nproperty float a\n");
  expect_refused(text + "7\n" + kVertices + "4 0 1 2 3\n",
                 "element 'camera' on line 3 is not one the PLY reader");
}

TEST_F(PlyCheck, NumbersAssimpWouldNotReadWholeAreRefused) {
  // 25 digits overflow Assimp's 64-bit parse, which then does not move past
  // them: the next value would be read from the same digits.
  expect_refused(
      header("ascii") + "0 0 0\n1 0 0\n1 1 0\n0 1 1000000000000000000000000\n4 0 1 2 3\n",
      "is not a whole number of its type");
  // A real where an integer is expected: Assimp would stop at the '.'.
  expect_refused(header("ascii") + kVertices + "4 0 1 2 3.5\n", "is not a whole integer");
}

TEST_F(PlyCheck, ControlCharactersThatAssimpTakesForLineEndsAreRefused) {
  std::string text = header("ascii");
  text.replace(text.find("element face 1"), 14, std::string("comment x\relement face 9", 24));
  expect_refused(text + kVertices + "4 0 1 2 3\n", "control character 13 in the header on line 7");
  expect_refused(header("ascii") + "0 0 0\n1 0\f0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
                 "control character 12 on line 11");
}

}  // namespace
}  // namespace bounce
