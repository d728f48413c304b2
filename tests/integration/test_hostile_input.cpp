// Hostile input to `bounce bake`: malformed and truncated
// OBJ, PLY, glTF and scene.json files, and exports onto a read-only folder or
// a full disk. Every case must end the same way: exit code 1 (not a signal,
// not the "internal error" code 3), before the timeout, with exactly one
// `bounce: error:` line naming the offending file, and no bake folder or
// hidden temporary folder left behind. test_cli_errors.cpp holds the basic
// cases (missing scene, JSON syntax error with line and column, NaN vertex);
// test_cli_solve.cpp the damaged bake folders.
#include <grp.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <cstdint>
#include <cstring>

#include "cli_harness.h"

namespace bounce::itest {
namespace {

// Two parallel unit squares facing each other, so that a bake of them works.
constexpr const char* kSquaresObj =
    "o bottom\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "f 1 2 3\nf 1 3 4\n"
    "o top\n"
    "v 0 0 1\nv 0 1 1\nv 1 1 1\nv 1 0 1\n"
    "f 5 6 7\nf 5 7 8\n";

constexpr const char* kLight = R"("lights": [{"name": "mid", "position": [0.5, 0.5, 0.5]}])";

std::string scene_json_for(const std::string& mesh_file) {
  return std::string(R"({"meshes": [{"file": ")") + mesh_file + R"("}], )" + kLight + "}\n";
}

// The PLY header of `vertices` vertices and `faces` triangles in `format`.
std::string ply_header(const std::string& format, int vertices = 4, int faces = 2) {
  return "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
         std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

// kSquaresObj as binary little-endian PLY data (after ply_header(..., 8, 4)).
std::string binary_ply_body() {
  std::string body;
  auto put = [&body](const void* p, std::size_t n) { body.append(static_cast<const char*>(p), n); };
  const float vertices[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                {0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}};
  put(vertices, sizeof vertices);
  const std::int32_t faces[4][3] = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  for (const auto& f : faces) {
    const std::uint8_t count = 3;
    put(&count, 1);
    put(f, sizeof f);
  }
  return body;
}

// A one-triangle glTF whose buffer is `buffer_uri` (byteLength 44: 3 float
// vertices, 3 uint16 indices, 2 padding bytes).
std::string gltf_with_buffer(const std::string& buffer_uri, int byte_length = 44) {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "buffers": [{"byteLength": )" +
         std::to_string(byte_length) + R"(, "uri": ")" + buffer_uri + R"("}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})";
}

constexpr const char* kTriangleBase64 =
    "data:application/octet-stream;base64,"
    "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=";

class HostileInput : public ::testing::Test {
 protected:
  TempDir tmp;
  fs::path out = tmp / "out";

  // Runs `bounce bake <input> --voxel 4 --out <out>` with a timeout well above
  // what a refusal needs, so a hang fails the test instead of blocking it.
  RunResult bake(const fs::path& input) {
    return run({"bake", input.string(), "--voxel", "4", "--out", out.string()}, tmp.path(), 30.0);
  }

  // The contract of a refused input: exit 1 in time, exactly one error line
  // naming `file` (and holding each of `needles`), nothing left behind.
  void expect_refused(const RunResult& r, const fs::path& file,
                      const std::vector<std::string>& needles = {}) {
    EXPECT_FALSE(r.timed_out) << r;
    EXPECT_LT(r.exit_code, 128) << "ended by a signal:\n" << r;
    EXPECT_EQ(r.exit_code, 1) << r;
    EXPECT_FALSE(contains(r.err, "internal error")) << r;
    const auto errors = lines_starting_with(r.err, "bounce: error: ");
    ASSERT_EQ(errors.size(), 1u) << r;
    EXPECT_TRUE(contains(errors[0], file.string()))
        << "the error does not name " << file << ": " << errors[0];
    for (const std::string& n : needles)
      EXPECT_TRUE(contains(errors[0], n)) << "error line lacks '" << n << "': " << errors[0];
    EXPECT_FALSE(fs::exists(out)) << "a refused bake created " << out;
    EXPECT_TRUE(hidden_leftovers(out).empty())
        << "hidden temporary folders left: " << testing::PrintToString(hidden_leftovers(out));
  }

  // Writes <tmp>/<name> and bakes it directly (a bare mesh file).
  void expect_mesh_refused(const std::string& name, const std::string& content,
                           const std::vector<std::string>& needles = {}) {
    SCOPED_TRACE(name);
    const fs::path file = tmp / name;
    write_text(file, content);
    expect_refused(bake(file), file, needles);
  }
};

// --- OBJ ---------------------------------------------------------------------

TEST_F(HostileInput, ObjFaceIndexOutOfRange) {
  expect_mesh_refused("out-of-range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
}

TEST_F(HostileInput, ObjTruncatedInsideTheFirstFace) {
  // Cut inside the first `f` line: the vertices are there, no complete triangle.
  const std::string whole = kSquaresObj;
  expect_mesh_refused("truncated.obj", whole.substr(0, whole.find("f 1 2 3") + 4));
}

TEST_F(HostileInput, ObjOfGarbageAndNulBytes) {
  std::string garbage = "v 0 0 0\nf \x01\x02\x03\n";
  garbage += std::string(64, '\0');
  garbage += "\xff\xfe v v v f f f\n";
  expect_mesh_refused("garbage.obj", garbage);
}

TEST_F(HostileInput, ObjWithNonNumericCoordinatesOnly) {
  expect_mesh_refused("words.obj",
                      "v one two three\nv four five six\nv seven eight nine\nf 1 2 3\n");
}

// --- PLY ---------------------------------------------------------------------

TEST_F(HostileInput, PlyAsciiWithFewerVerticesThanTheHeaderSays) {
  expect_mesh_refused("short.ply", ply_header("ascii") + "0 0 0\n1 0 0\n");
}

TEST_F(HostileInput, PlyAsciiFaceIndexOutOfRange) {
  expect_mesh_refused("bad-index.ply",
                      ply_header("ascii") + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 99\n");
}

TEST_F(HostileInput, PlyBinaryTruncatedAnywhere) {
  const std::string header = ply_header("binary_little_endian", 8, 4);
  const std::string body = binary_ply_body();
  // The whole file loads (checked, so the cuts below test truncation and
  // not a header the reader never accepted).
  {
    const fs::path whole = tmp / "whole.ply";
    write_text(whole, header + body);
    const RunResult r = bake(whole);
    ASSERT_EQ(r.exit_code, 0) << "the untruncated PLY must bake:\n" << r;
    fs::remove_all(out);
  }
  for (const std::size_t keep :
       {std::size_t{0}, body.size() / 3, 2 * body.size() / 3, body.size() - 1}) {
    SCOPED_TRACE("body bytes kept: " + std::to_string(keep) + " of " + std::to_string(body.size()));
    const fs::path file = tmp / ("cut-" + std::to_string(keep) + ".ply");
    write_text(file, header + body.substr(0, keep));
    expect_refused(bake(file), file);
  }
}

TEST_F(HostileInput, PlyWithHugeElementCount) {
  // Claims four billion vertices in a file of a few bytes: must not try to
  // allocate or read them.
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  expect_mesh_refused("huge-count.ply", header + std::string(24, '\0'));
}

// --- glTF --------------------------------------------------------------------

TEST_F(HostileInput, GltfWithBrokenJson) {
  const std::string whole = gltf_with_buffer(kTriangleBase64);
  expect_mesh_refused("broken.gltf", whole.substr(0, whole.size() / 2));
}

TEST_F(HostileInput, GltfWithMissingBufferFile) {
  expect_mesh_refused("missing-buffer.gltf", gltf_with_buffer("missing.bin"));
}

TEST_F(HostileInput, GltfWithBufferShorterThanItsViews) {
  // The accessors need 42 bytes; the buffer holds 8.
  expect_mesh_refused("short-buffer.gltf",
                      gltf_with_buffer("data:application/octet-stream;base64,AAAAAAAAAAA=", 8));
}

// --- scene.json --------------------------------------------------------------

class HostileSceneJson : public HostileInput {
 protected:
  // Writes <tmp>/scene/scene.json (next to a good squares.obj) and bakes it.
  void expect_scene_refused(const std::string& scene_json,
                            const std::vector<std::string>& needles = {}) {
    const fs::path dir = tmp / "scene";
    write_text(dir / "squares.obj", kSquaresObj);
    write_text(dir / "scene.json", scene_json);
    expect_refused(bake(dir), dir / "scene.json", needles);
  }
};

TEST_F(HostileSceneJson, TheGoodSceneBakes) {
  // The baseline every refusal below departs from by one change.
  const fs::path dir = tmp / "scene";
  write_text(dir / "squares.obj", kSquaresObj);
  write_text(dir / "scene.json", scene_json_for("squares.obj"));
  const RunResult r = bake(dir);
  ASSERT_EQ(r.exit_code, 0) << r;
  EXPECT_TRUE(fs::exists(out / "manifest.json"));
}

TEST_F(HostileSceneJson, EmptyFileTruncatedFileAndBinaryGarbage) {
  const std::string good = scene_json_for("squares.obj");
  for (const std::string& text :
       {std::string(), good.substr(0, good.size() / 2), std::string("\x00\xff\x13{", 4)}) {
    SCOPED_TRACE(testing::PrintToString(text));
    expect_scene_refused(text);
  }
}

TEST_F(HostileSceneJson, NaNAndInfinityAreNotJson) {
  for (const std::string value : {"NaN", "-Infinity"}) {
    SCOPED_TRACE(value);
    expect_scene_refused(R"({"meshes": [{"file": "squares.obj"}], )"
                         R"("lights": [{"position": [)" +
                         value + R"(, 0, 0]}]})");
  }
}

TEST_F(HostileSceneJson, NumbersTooLargeForADouble) {
  expect_scene_refused(R"({"meshes": [{"file": "squares.obj", "transform": {"scale": 1e999}}]})",
                       {"1e999"});
}

TEST_F(HostileSceneJson, ScaleThatOverflowsTheVerticesToInfinity) {
  // 1e300 is a finite double, but the scaled vertices do not fit a float.
  expect_scene_refused(
      std::string(R"({"meshes": [{"file": "squares.obj", "transform": {"scale": 1e300}}], )") +
      kLight + "}");
}

TEST_F(HostileSceneJson, HugeIntegersForCounts) {
  for (const std::string value : {"18446744073709551616", "-1", "2.5"}) {
    SCOPED_TRACE(value);
    expect_scene_refused(std::string(R"({"meshes": [{"file": "squares.obj"}], )") + kLight +
                             R"(, "bake": {"voxel": )" + value + "}}",
                         {"bake.voxel"});
  }
}

TEST_F(HostileSceneJson, PatchDensityThatIsNotAPositiveNumberIsNamed) {
  for (const std::string value : {"0", "-1", R"("x")", "1e300", "65", "null"}) {
    SCOPED_TRACE(value);
    expect_scene_refused(
        R"({"meshes": [{"file": "squares.obj", "patch_density": )" + value + "}], " + kLight + "}",
        {"meshes[0].patch_density", "> 0 and <= 64"});
  }
  // Not JSON at all: refused at its position like any other NaN.
  expect_scene_refused(R"({"meshes": [{"file": "squares.obj", "patch_density": NaN}]})");
}

TEST_F(HostileSceneJson, WrongTypesAtTheTop) {
  for (const std::string text : {"[]", "null", R"({"meshes": {}})", R"({"meshes": [{"file": 7}]})",
                                 R"({"meshes": [{"file": "squares.obj"}], "lights": {}})"}) {
    SCOPED_TRACE(text);
    expect_scene_refused(text);
  }
}

TEST_F(HostileSceneJson, DeeplyNestedArrays) {
  // Nesting deep enough to overflow a recursive parser's or destructor's
  // stack; `meshes[0]` must be an object, so the scene is refused.
  const std::size_t depth = 100000;
  expect_scene_refused(R"({"meshes": [)" + std::string(depth, '[') + std::string(depth, ']') + "]}",
                       {"meshes[0]"});
}

TEST_F(HostileSceneJson, MissingMeshFileIsNamed) {
  const fs::path dir = tmp / "scene";
  write_text(dir / "scene.json", scene_json_for("nowhere/missing.obj"));
  expect_refused(bake(dir), dir / "nowhere" / "missing.obj", {"no such file", "meshes[0].file"});
}

TEST_F(HostileSceneJson, MeshPathThatIsAFolderIsNamed) {
  const fs::path dir = tmp / "scene";
  fs::create_directories(dir / "folder.obj");
  write_text(dir / "scene.json", scene_json_for("folder.obj"));
  expect_refused(bake(dir), dir / "folder.obj", {"not a regular file", "meshes[0].file"});
}

TEST_F(HostileSceneJson, MeshPathThatIsADeviceIsNamed) {
  const fs::path dir = tmp / "scene";
  write_text(dir / "scene.json", scene_json_for("/dev/zero"));
  expect_refused(bake(dir), "/dev/zero", {"not a regular file"});
}

TEST_F(HostileSceneJson, MeshFileThatIsTheSceneJsonItself) {
  const fs::path dir = tmp / "scene";
  write_text(dir / "scene.json", scene_json_for("scene.json"));
  expect_refused(bake(dir), dir / "scene.json");
}

// --- Export failures ---------------------------------------------------------

// Runs `bounce args...` in `cwd` under `confinement` (RunOptions: as the
// `nobody` user and/or with a file size limit).
RunResult run_confined(const std::vector<std::string>& args, const fs::path& cwd,
                       RunOptions confinement) {
  confinement.cwd = cwd;
  return run(args, confinement);
}

// Why `nobody` cannot run `program` here, or "" when it can. A child drops
// to `nobody` the way the harness does and asks the kernel whether it may
// execute the program, which covers every folder above it (a clone in a
// home folder of mode 0700 fails here) and a noexec mount.
std::string why_nobody_cannot_run(const fs::path& program) {
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0) return std::string("pipe2: ") + std::strerror(errno);
  const pid_t pid = ::fork();
  if (pid < 0) return std::string("fork: ") + std::strerror(errno);
  if (pid == 0) {
    int step = 0;
    if (::setgroups(0, nullptr) != 0 || ::setgid(kNobody) != 0 || ::setuid(kNobody) != 0)
      step = 1;
    else if (::access(program.c_str(), X_OK) != 0)
      step = 2;
    const int answer[2] = {step, errno};
    [[maybe_unused]] const ssize_t written = ::write(report[1], answer, sizeof answer);
    ::_exit(0);
  }
  ::close(report[1]);
  int answer[2] = {0, 0};
  ssize_t got = 0;
  do {
    got = ::read(report[0], answer, sizeof answer);
  } while (got < 0 && errno == EINTR);
  ::close(report[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (got != static_cast<ssize_t>(sizeof answer)) return "the probe process did not answer";
  if (answer[0] == 1)
    return std::string("cannot switch to user nobody (") + std::strerror(answer[1]) +
           "): no CAP_SETUID here";
  if (answer[0] != 2) return "";
  std::string why =
      "user nobody cannot execute " + program.string() + " (" + std::strerror(answer[1]) + ")";
  for (fs::path dir = program.parent_path(); !dir.empty(); dir = dir.parent_path()) {
    struct stat st {};
    if (::stat(dir.c_str(), &st) == 0 && (st.st_mode & S_IXOTH) == 0 && st.st_uid != kNobody) {
      why += ": " + dir.string() +
             " is not searchable by others; set TMPDIR to a folder they can enter";
      break;
    }
    if (dir == dir.root_path()) break;
  }
  return why;
}

class ExportFailure : public HostileInput {
 protected:
  void SetUp() override {
    // The scene must be readable by `nobody`: the temp folder is 0700.
    fs::permissions(tmp.path(), kOthersEnter);
    scene_dir = tmp / "scene";
    write_text(scene_dir / "squares.obj", kSquaresObj);
    write_text(scene_dir / "scene.json", scene_json_for("squares.obj"));
  }

  // Root ignores permission bits, so as root the bake runs as `nobody`.
  // The build tree may lie where `nobody` cannot reach it (a clone in
  // /root, mode 0700), so it runs a copy of `bounce` placed in this test's
  // folder. The copy needs nothing else from the build tree: bounce_core is
  // a static library and the OpenCL kernels are compiled into it. Returns
  // the reason when `nobody` cannot run even the copy (no CAP_SETUID, a
  // temp folder under a private folder, a noexec mount).
  std::string run_as_nobody(RunOptions& confinement) {
    const fs::path bin = tmp / "bin";
    fs::create_directories(bin);
    fs::permissions(bin, kOthersEnter);
    const fs::path copy = bin / "bounce";
    fs::copy_file(kCli, copy, fs::copy_options::overwrite_existing);
    fs::permissions(copy, kOthersEnter);
    confinement.as_nobody = true;
    confinement.program = copy;
    return why_nobody_cannot_run(copy);
  }

  // `force`: bake even onto an up-to-date bake of the same scene and settings.
  RunResult bake_confined(const fs::path& target, const RunOptions& c, bool force = false) {
    // Quiet: the file size limit of the full-disk case applies to the
    // child's captured stderr too, and progress lines would fill it first.
    std::vector<std::string> args = {"bake",  scene_dir.string(), "--voxel", "4", "--quiet",
                                     "--out", target.string()};
    if (force) args.push_back("--force");
    return run_confined(args, tmp.path(), c);
  }

  // One error line naming the bake folder `target`, holding `why`.
  static void expect_export_error(const RunResult& r, const fs::path& target,
                                  const std::string& why) {
    EXPECT_FALSE(r.timed_out) << r;
    EXPECT_EQ(r.exit_code, 1) << r;
    EXPECT_FALSE(contains(r.err, "internal error")) << r;
    const auto errors = lines_starting_with(r.err, "bounce: error: ");
    ASSERT_EQ(errors.size(), 1u) << r;
    EXPECT_TRUE(contains(errors[0], target.string()))
        << "the error does not name " << target << ": " << errors[0];
    EXPECT_TRUE(contains(errors[0], why)) << "error line lacks '" << why << "': " << errors[0];
    EXPECT_TRUE(hidden_leftovers(target).empty())
        << "hidden temporary folders left: " << testing::PrintToString(hidden_leftovers(target));
  }

  // rwxr-xr-x: others may enter (and read) but not write.
  static constexpr fs::perms kOthersEnter = fs::perms::owner_all | fs::perms::group_read |
                                            fs::perms::group_exec | fs::perms::others_read |
                                            fs::perms::others_exec;
  fs::path scene_dir;
};

TEST_F(ExportFailure, ReadOnlyFolderIsRefusedWithoutLeftovers) {
  const fs::path parent = tmp / "read-only";
  fs::create_directories(parent);
  fs::permissions(parent, kOthersEnter);
  RunOptions c;
  if (::geteuid() == 0) {
    const std::string why_not = run_as_nobody(c);
    if (!why_not.empty()) GTEST_SKIP() << "cannot run the bake without root's rights: " << why_not;
  } else {
    fs::permissions(parent, fs::perms::owner_write, fs::perm_options::remove);
  }
  const fs::path target = parent / "bake";
  const RunResult r = bake_confined(target, c);
  expect_export_error(r, target, "Permission denied");
  EXPECT_TRUE(fs::is_empty(parent)) << testing::PrintToString(entries(parent));
}

TEST_F(ExportFailure, PreviousBakeInAReadOnlyFolderStaysIntact) {
  // A good bake first, then a second bake onto it as a user who may not
  // write in its parent: the old bake must survive unchanged.
  const fs::path parent = tmp / "read-only";
  const fs::path target = parent / "bake";
  {
    const RunResult first = bake_confined(target, {});
    ASSERT_EQ(first.exit_code, 0) << first;
  }
  const std::string manifest_before = read_text(target / "manifest.json");
  const std::vector<std::string> files_before = entries(target);
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to run the second bake as another user";
  fs::permissions(parent, kOthersEnter);
  RunOptions c;
  const std::string why_not = run_as_nobody(c);
  if (!why_not.empty()) GTEST_SKIP() << "cannot run the bake without root's rights: " << why_not;
  // Forced: the first bake is up to date and would be kept without a write.
  const RunResult r = bake_confined(target, c, true);
  expect_export_error(r, target, "Permission denied");
  EXPECT_EQ(entries(target), files_before);
  EXPECT_EQ(read_text(target / "manifest.json"), manifest_before);
  EXPECT_EQ(entries(parent), std::vector<std::string>{"bake"});
}

TEST_F(ExportFailure, FullDiskIsAClearErrorWithoutLeftovers) {
  // patches.npy alone holds 15 floats per patch, more than 1 KiB for this
  // scene, so a 1 KiB file size limit makes a write fail partway.
  const fs::path target = tmp / "bakes" / "bake";
  RunOptions c;
  c.max_file_bytes = 1024;
  const RunResult r = bake_confined(target, c);
  expect_export_error(r, target, "write failed");
  EXPECT_FALSE(fs::exists(target));
  EXPECT_TRUE(fs::is_empty(target.parent_path()))
      << testing::PrintToString(entries(target.parent_path()));
}

}  // namespace
}  // namespace bounce::itest
