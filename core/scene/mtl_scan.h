#pragma once
// Which OBJ materials really state a diffuse colour. Assimp's OBJ importer
// gives every material a diffuse colour, inventing 0.6 grey when the MTL has
// no `Kd` line, when the MTL file is missing, or when `usemtl` names a
// material nobody defined. A made-up albedo would change the bake silently,
// so the loader reads the MTL files itself (only `mtllib`, `newmtl`, `Kd` and `Ke`)
// to tell stated colours from invented ones; `Ke` likewise, so that an
// emissive texture without an emissive colour takes factor 1 as a colour
// texture without `Kd` does. Internal to the scene module.
#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace bounce::scene_internal {

struct MtlScan {
  std::set<std::string> with_diffuse;            // material names that have a Kd line
  std::set<std::string> with_emissive;           // material names that have a Ke line
  std::vector<std::string> missing_libraries;    // `mtllib` names that could not be opened
  std::vector<std::filesystem::path> libraries;  // the MTL files read, in `mtllib` order
};

// Reads the `mtllib` lines of `obj` and the MTL files they name, resolving
// them like Assimp 5.2 does (next to the OBJ; else "<obj minus extension>.mtl").
MtlScan scan_obj_materials(const std::filesystem::path& obj);

}  // namespace bounce::scene_internal
