#pragma once
// Light on virtual patches -> light on the scene's own triangles, for display
// and export (PLY). The scene's triangle soup becomes an OpenMesh
// half-edge mesh that is refined until every edge is shorter than half a
// voxel (a Cornell wall is two triangles: four vertices cannot carry light
// that changes voxel by voxel), gets normals that respect creases, and each
// vertex takes the light of the patches around it (runtime/patch_gather.h).
//
// The geometry depends only on the scene and the grid, the light changes
// every frame: build_transfer_mesh() once, relight() per light vector;
// transfer_to_mesh() does both.
//
// Triangle soups are not always manifold. OpenMesh's add_face refuses a face
// that would make an edge with more than two faces or a vertex joining two
// fans ("complex edge/vertex"); such a face gets its own copies of its three
// vertices instead of being dropped, and is counted. Two-sided meshes get a
// back copy of each face, facing the other way, with its own vertices, so
// each side carries the light of its own side.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "patches/patch_set.h"
#include "raytrace/ray_tracer.h"
#include "runtime/patch_gather.h"
#include "scene/scene.h"

namespace bounce {

struct TransferSettings {
  GatherSettings gather;
  // Edges longer than this many voxel sizes are split (longest first):
  // half a voxel gives at least two vertices per voxel along a wall, about
  // the spacing of the patches themselves (~3 per voxel).
  float max_edge_cells = 0.5f;
  // Faces meeting at more than this angle do not share a vertex normal: a
  // box corner's vertex becomes one vertex per wall, each with its wall's
  // normal, instead of one normal averaged over three walls that agrees with
  // none of them.
  float crease_angle_deg = 45.0f;
  // Refinement stops with an error beyond this many faces (a very fine grid
  // on a large scene) rather than exhausting memory.
  std::size_t max_faces = 20'000'000;
};

struct LitMeshCounts {
  std::size_t scene_triangles = 0;
  std::size_t vertices = 0;          // output vertices (after crease splits)
  std::size_t faces = 0;             // output triangles
  std::size_t split_edges = 0;       // edge splits made by refinement
  std::size_t duplicated_faces = 0;  // non-manifold faces given their own vertices
  std::size_t back_faces = 0;        // back copies of two-sided faces
  std::size_t crease_vertices = 0;   // extra vertices made by splitting normals at creases
  std::size_t dark_vertices = 0;     // no visible, agreeing patch even after widening
  std::size_t widened_vertices = 0;  // needed the 5x5x5 search
  std::size_t occlusion_rays = 0;
};

struct LitMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;     // unit, per vertex
  std::vector<glm::vec3> radiosity;   // light leaving each vertex, same units as the patches'
  std::vector<glm::uvec3> triangles;  // counter-clockwise = front
  std::vector<std::uint32_t> source_triangle;  // scene triangle each face comes from
  LitMeshCounts counts;
};

// The refined mesh with normals, radiosity all zero. Throws bounce::Error for
// settings out of range or when max_faces is exceeded, Cancelled on a stop.
LitMesh build_transfer_mesh(const Scene& scene, const TransferGrid& grid,
                            const TransferSettings& settings, Progress* progress = nullptr);

// The scene triangle each vertex stands on (one of its faces'; 0 for a
// vertex no face uses), for its material.
std::vector<std::uint32_t> vertex_source_triangles(const LitMesh& mesh);

// Fills mesh.radiosity from the gather and the dark/widened/ray counts.
void relight(LitMesh& mesh, const PatchGather& gather, Progress* progress = nullptr);

// Both, on tracer.scene(): `light` is the light leaving each patch (e.g. the
// first-hit b plus the indirect T b).
LitMesh transfer_to_mesh(const RayTracer& tracer, const std::vector<Patch>& patches,
                         const TransferGrid& grid, const std::vector<glm::vec3>& light,
                         const TransferSettings& settings, Progress* progress = nullptr);

}  // namespace bounce
