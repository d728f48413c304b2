// libFuzzer target: a mesh file given directly to SceneLoader::load, as in
// `bounce bake model.obj`. Assimp picks the reader by extension, so this file
// is built once per format with BOUNCE_FUZZ_MESH_EXTENSION (".obj", ".ply",
// ".gltf"); each binary's corpus holds real files of its format. Every input
// must either load or throw bounce::Error.
#include <cstddef>
#include <cstdint>
#include <string>

#include "base/diagnostics.h"
#include "base/error.h"
#include "fuzz_workdir.h"
#include "scene/scene_loader.h"

#ifndef BOUNCE_FUZZ_MESH_EXTENSION
#error "BOUNCE_FUZZ_MESH_EXTENSION must name the mesh format, e.g. \".obj\""
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file =
      bounce::fuzz::work_dir().write(std::string("mesh") + BOUNCE_FUZZ_MESH_EXTENSION, data, size);
  bounce::Diagnostics diagnostics;
  try {
    (void)bounce::SceneLoader(diagnostics).load(file);
  } catch (const bounce::Error&) {
    // The expected way to refuse bad input: one message naming the file.
  }
  return 0;
}
