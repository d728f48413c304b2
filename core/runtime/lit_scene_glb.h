#pragma once
// A lit mesh (runtime/mesh_transfer.h) with its scene's materials and
// textures as binary glTF (io/glb_writer.h, runtime/glb_materials.h): one
// primitive per glTF material, TEXCOORD_0 from the scene's texture
// coordinates on the primitives that have a texture or a mask.
//
// What COLOR_0 holds (before exposure and clamping):
//   plain materials      the vertex's light, emission + albedo x irradiance
//                        (LitMesh::radiosity, as the PLY holds it);
//   textured materials   the light without the albedo: the vertex's
//                        radiosity less the emission of the material it was
//                        lit with, divided by that material's (mean)
//                        albedo, per channel (0 where the albedo is 0). A
//                        viewer's factor x texel x COLOR_0 is then the
//                        texel's own albedo times the light reaching it.
// The exposure is ToneMap's (io/tone_map.h) over one such value per lit
// vertex: the PLY's exposure when no material is textured. _RADIANCE is the
// radiosity, exact, whatever the material.
//
// The lit mesh shares a vertex between faces with the same normal; where
// those faces' materials or texture coordinates differ (a seam), the vertex
// is split, each copy keeping its light. A scene without textured or masked
// materials gives one primitive holding the lit mesh as it is, vertex for
// vertex.
#include <filesystem>
#include <string>

#include "runtime/mesh_transfer.h"
#include "scene/scene.h"

namespace bounce {

// Writes `mesh`, lit and built on `scene`, to `path`; `name` is what a
// viewer lists it as. Returns the exposure. Throws what write_glb and
// glb_materials throw, and bounce::Error when the mesh is not the scene's.
float write_lit_scene_glb(const std::filesystem::path& path, const Scene& scene,
                          const LitMesh& mesh, const std::string& name);

}  // namespace bounce
