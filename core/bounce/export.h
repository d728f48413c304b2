#pragma once
// Public: write a lit mesh for other tools.
//
//   bounce::write_lit_ply(out / "lit.ply", {mesh.positions, mesh.normals, mesh.radiosity,
//                                           mesh.triangles});
//   bounce::write_lit_glb(out / "lit.glb", {mesh.positions, mesh.normals, mesh.radiosity,
//                                           mesh.triangles});
//
// PLY for mesh tools and scripts (exact linear light per vertex beside the
// tone-mapped colours, extra per-vertex figures); binary glTF for Blender and
// web viewers (tone-mapped linear COLOR_0 on an unlit material, the exact
// light as _RADIANCE). Both tone-map with the same exposure and are written
// atomically.
#include "io/glb_writer.h"
#include "io/ply_writer.h"
