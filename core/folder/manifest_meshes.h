#pragma once
// The manifest's per-mesh table (`meshes`, docs/bake-format.md): each mesh's
// name, the patch density its patches were made with, how many patches it
// got and its area. What the studio's mesh list shows of a bake, and what a
// density edit is checked against.
#include <cstddef>
#include <string>
#include <vector>

#include "folder/bake_reader.h"

namespace bounce {

struct ManifestMesh {
  std::string name;
  float patch_density = 1.0f;
  std::size_t patches = 0;  // patches whose largest share of area is this mesh's
  double area = 0.0;
};

// In mesh order (Scene::meshes). Empty when the manifest has no `meshes`
// (bakes made before it was written). Throws BakeReader::ReadError naming
// the bake's manifest.json when `meshes` is not an array of objects with
// these four fields of the right types, or when its patches do not add up
// to the bake's patch count.
std::vector<ManifestMesh> manifest_meshes(const LoadedBake& bake);

}  // namespace bounce
