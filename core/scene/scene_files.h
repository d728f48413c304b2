#pragma once
// The files a loaded scene was read from: its scene.json (or bare mesh file),
// every mesh file, what the mesh files pull in themselves (an OBJ's MTL
// libraries, a .gltf's external buffers) and every texture, mask and normal
// map read from a file. What a cache of results keyed by the scene's content
// hashes (bake/bake_key.h).
#include <filesystem>
#include <vector>

#include "scene/scene.h"

namespace bounce {

// In a fixed order (scene file, then the meshes in scene order with their
// companions, then the materials' images in material order), each file once.
// Empty for a scene not loaded from a file (Scene::path empty).
std::vector<std::filesystem::path> scene_source_files(const Scene& scene);

}  // namespace bounce
