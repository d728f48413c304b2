// libFuzzer target: a scene.json through SceneLoader::load, exactly as
// `bounce bake <folder>` loads it. The folder also holds `mesh.obj` (two
// facing squares) and `mesh.mtl`, so inputs that name that mesh get past the
// JSON checks into import and the scene builder. Every input must either load
// or throw bounce::Error; anything else (crash, sanitizer report, another
// exception type, leak) is a defect.
#include <cstddef>
#include <cstdint>

#include "base/diagnostics.h"
#include "base/error.h"
#include "fuzz_workdir.h"
#include "scene/scene_loader.h"

namespace {

constexpr char kMeshObj[] =
    "mtllib mesh.mtl\n"
    "o bottom\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl grey\nf 1 2 3\nf 1 3 4\n"
    "o top\nv 0 0 1\nv 0 1 1\nv 1 1 1\nv 1 0 1\nusemtl light\nf 5 6 7\nf 5 7 8\n";
constexpr char kMeshMtl[] = "newmtl grey\nKd 0.5 0.5 0.5\nnewmtl light\nKd 0.8 0.8 0.8\nKe 1 1 1\n";

template <std::size_t N>
void write_fixture(const char* name, const char (&text)[N]) {
  bounce::fuzz::work_dir().write(name, reinterpret_cast<const std::uint8_t*>(text), N - 1);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  write_fixture("mesh.obj", kMeshObj);
  write_fixture("mesh.mtl", kMeshMtl);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto json = bounce::fuzz::work_dir().write("scene.json", data, size);
  bounce::Diagnostics diagnostics;
  try {
    (void)bounce::SceneLoader(diagnostics).load(json);
  } catch (const bounce::Error&) {
    // The expected way to refuse bad input: one message naming the file.
  }
  return 0;
}
