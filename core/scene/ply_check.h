#pragma once
// A structural check of PLY files before Assimp reads them. Assimp 5.2's PLY
// reader (Debian 12) reads past the end of its buffer on a header without
// `end_header` and on binary bodies shorter than the header declares; it
// crashes (SEGV) instead of reporting an error. Fuzzing found both (see
// docs/stability.md). This reads only the header and the file size, and
// throws SceneLoader::LoadError naming the file when the file cannot hold what
// its header declares. Internal to the scene module.
#include <filesystem>

namespace bounce::scene_internal {

// True if the file starts with the PLY magic line ("ply").
bool looks_like_ply(const std::filesystem::path& file);

// Throws SceneLoader::LoadError if the header is malformed (no `end_header`,
// unknown format or property type, bad element count) or, for the binary
// formats, if the body is shorter than the smallest size the header allows
// (lists counted as empty).
void check_ply_structure(const std::filesystem::path& file);

}  // namespace bounce::scene_internal
