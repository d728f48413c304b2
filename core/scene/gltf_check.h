#pragma once
// A structural check of glTF files before Assimp reads them. Assimp 5.2
// (Debian 12) reads a primitive's vertex count from its POSITION accessor and
// makes count - 1 lines of a line strip without checking the count: a
// primitive without POSITION gave 4,294,967,295 faces, a 64 GB request
// (fuzzing). Its JSON parser also accepts bytes that are not UTF-8, which the
// glTF format forbids, and it reads an image's media type (its mimeType, or
// the type its data URI names) from after a '/' it never looks for: "x" or
// "image" crashed the process (SIGSEGV, fuzzing). This parses the JSON part
// (a .gltf file, or the JSON chunk of a .glb) strictly and checks that every
// mesh primitive names a POSITION accessor that exists and holds at least
// one vertex, that its indices, when it has them, do too, and that every
// image's media type, when it names one, has a '/'. It throws
// SceneLoader::LoadError naming the file and the mesh and primitive or the
// image otherwise. Internal to the scene module.
#include <filesystem>

namespace bounce::scene_internal {

// True for a .gltf or .glb name, or a file that starts with the binary glTF
// magic ("glTF"): Assimp picks its glTF reader by either.
bool looks_like_gltf(const std::filesystem::path& file);

// Throws SceneLoader::LoadError if the JSON is malformed (not UTF-8, not
// JSON, a .glb whose JSON chunk runs past the file), a mesh primitive
// cannot be read safely (no POSITION, an accessor index out of range or an
// accessor with no elements) or an image's media type has no '/'.
void check_gltf_structure(const std::filesystem::path& file);

}  // namespace bounce::scene_internal
