#pragma once
// Public: write a lit mesh for other tools.
//
//   bounce::write_lit_ply(out / "lit.ply", {mesh.positions, mesh.normals, mesh.radiosity,
//                                           mesh.triangles});
//   bounce::write_lit_scene_glb(out / "lit.glb", scene, mesh, "my-scene");
//
// PLY for mesh tools and scripts (exact linear light per vertex beside the
// tone-mapped colours, extra per-vertex figures); binary glTF for Blender and
// web viewers: the scene's materials, their textures embedded and texture
// coordinates, tone-mapped linear COLOR_0 on unlit materials (the light
// without the albedo where a texture carries it), the exact light as
// _RADIANCE. write_lit_glb writes a bare mesh without materials. All are
// written atomically; AtomicFile writes a front end's own files the same
// way (a temporary name renamed into place by commit(), so an interrupted
// write leaves no half file).
#include "io/atomic_file.h"
#include "io/glb_writer.h"
#include "io/ply_writer.h"
#include "runtime/lit_scene_glb.h"
