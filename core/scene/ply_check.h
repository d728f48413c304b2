#pragma once
// A structural check of PLY files before Assimp reads them. Assimp 5.2's PLY
// reader (Debian 12) reads past the end of its buffer on a header without
// `end_header` and on binary bodies shorter than the header declares, and
// allocates whatever element or list count it reads before reading the data
// (fuzzing: 31 and 63 GB requests). This reads the header the way Assimp does,
// refuses what Assimp would read differently from the format, and walks the
// body so that every element count and every list count is backed by values
// in the file. It throws SceneLoader::LoadError naming the file (and the
// element) otherwise. Internal to the scene module.
#include <filesystem>

namespace bounce::scene_internal {

// True if the file starts with the PLY magic line ("ply").
bool looks_like_ply(const std::filesystem::path& file);

// Throws SceneLoader::LoadError if the header is malformed (no `end_header`,
// unknown format, keyword, element or property type, bad element count) or
// the body does not hold what the header declares: binary items and lists
// that run past the end of the file; ascii items that are not one line of
// whole numbers of their types, with each list as long as its count.
void check_ply_structure(const std::filesystem::path& file);

}  // namespace bounce::scene_internal
