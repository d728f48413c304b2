#pragma once
// Surface samples inside each occupied voxel: points
// spread evenly over the voxel's six faces, rays traced into the voxel, hits
// inside the voxel kept with the hit triangle's normal and material.
//
// Directions are cosine-distributed about each face's inward normal: rays
// entering a convex cell uniformly over its boundary with cosine-weighted
// directions are isotropic random lines (Crofton), so every surface in the
// cell is hit with a density proportional to its area whatever its
// orientation; every hit along a ray inside the cell is kept, not just the first.
//
// Area of a sample: the published virtual-patch method gives each of the K samples on a triangle
// part S = S_tri∩voxel / K. We split the part into the Voronoi cells of its K samples instead: the
// same areas on average (they add up to S exactly), but each sample now stands for the piece of
// surface around it, a polygon the form factors integrate over near edges and corners. Triangle
// parts that no ray hit (tiny triangles) go whole to the nearest sample of the same voxel on the
// same surface (facing the same way, the part within kSameSurfaceCells of the sample's plane), or,
// without one, to a sample of their own at their centre: every part of the surface is carried by a
// sample that stands on it, so a voxel's sample areas add up to its surface
// area and light found anywhere on the surface belongs to some sample.
//
// Alpha-masked triangles: sampling rays pass their holes, so no sample lands
// on a cut-away point. Each piece of such a triangle (a Voronoi cell, or a
// part no ray hit) is carried with its area times its solid fraction (the
// share of it where the mask keeps the surface, from a lattice of mask
// lookups), its polygon unchanged; a piece wholly cut away is carried by
// nobody and gets no sample of its own. So a partly cut triangle's samples
// stand for just its solid area, though their polygons (used to place
// light over the surface) still span the holes within them; their albedo is
// the texture's mean over the solid part of those polygons only
// (Scene::mean_albedo), so what the holes' texels hold counts nowhere.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "raytrace/ray_tracer.h"
#include "voxel/voxelization.h"

namespace bounce {

// A sample stands for surface within this many voxel sizes of its plane; one
// farther off is on another surface (a curved surface's own samples lie
// within its sagitta over one voxel, far less).
inline constexpr float kSameSurfaceCells = 0.25f;

struct Sample {
  glm::vec3 position;
  glm::vec3 normal;  // unit; the side of the triangle the sample lies on
  glm::vec3 albedo;
  glm::vec3 emission;
  float area;
  std::uint32_t voxel;  // index into Voxelization::voxels
  std::uint32_t triangle;
  std::uint32_t mesh;
};

// A piece of surface a sample stands for: its Voronoi cell within one side of
// one triangle part (or a whole part no ray hit), as a planar polygon.
struct CarriedArea {
  std::uint32_t part;  // index into Voxelization::parts
  bool back;           // the back side of a two-sided triangle
  float area;
  std::uint32_t first_vertex;  // into SampleSet::carried_vertices
  std::uint32_t vertex_count;
  bool whole_part;  // a part no ray hit, given whole to this sample
  // The part's scene triangle: what a bake folder keeps of the part, so that
  // a bake read back (no voxelization) can still look up surface points.
  // kUnknownTriangle in bakes made before folders kept it.
  std::uint32_t triangle;
  static constexpr std::uint32_t kUnknownTriangle = 0xffffffffu;
};

struct SampleSet {
  std::vector<Sample> samples;  // grouped by voxel, in voxel order
  // What surface each sample stands for: carried[carried_first[s] .. carried_first[s+1]).
  std::vector<CarriedArea> carried;
  std::vector<std::uint32_t> carried_first;
  std::vector<glm::vec3> carried_vertices;
  std::vector<std::uint32_t> first;  // samples of voxel v: [first[v], first[v+1])
  double sampled_area = 0.0;         // total area carried by samples
  double surface_area = 0.0;         // total area of the sampled sides of all triangles
  // Parts no ray hit and no sample on their surface could carry: each got
  // a sample of its own at its centre. Their area and how many.
  double centre_sampled_area = 0.0;
  std::size_t centre_samples = 0;
  // Area of sampled sides that alpha masks cut away (not carried by any sample).
  double cut_away_area = 0.0;
  std::uint32_t voxels_without_samples = 0;
};

struct SamplingSettings {
  int samples_per_face = 4;  // a g x g jittered grid of ray origins on each face
  std::uint64_t seed = 1;
  std::size_t max_hits_per_ray = 16;
};

SampleSet generate_samples(const Scene& scene, const RayTracer& tracer, const Voxelization& vox,
                           const SamplingSettings& settings, Progress* progress = nullptr);

// Albedo and emission of samples on textured or vertex-coloured surfaces:
// the mean of the albedo (colour texture times vertex colour) and of the
// emission (emissive texture) over the surface each sample stands for (its
// carried polygons, weighted by area), not the value under its position, so
// that the light a patch reflects or emits follows the mean over the patch.
// Samples carrying no textured or coloured surface keep their material's
// values, bit for bit. Returns how many samples changed.
std::size_t apply_surface_textures(const Scene& scene, const Voxelization& vox, SampleSet& set,
                                   Progress* progress = nullptr);

}  // namespace bounce
