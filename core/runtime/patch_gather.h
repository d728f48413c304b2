#pragma once
// Light on virtual patches -> light at any surface point (the
// transfer from patches back to the original mesh). A patch has no geometry, only a
// position inside its voxel, a normal and the light leaving it, so a point x
// with normal n takes a normalised weighted mean of the patches around it:
//
//   w_p = (1 - d^2 / R^2)^2 * max(0, n . n_p)^k * V(x, p),   d = |x - p| < R,
//
// d and R in voxel units, R = 1, k = 4. Weights are normalised, so a constant
// light on the patches gives exactly that constant back.
//
// * Where: the patches of the point's voxel and its 26 neighbours. Patches are
//   binned by their own position (the centroid of samples inside their voxel,
//   so the same cell as Patch::voxel up to rounding on cell planes). The
//   kernel reaches zero at one voxel, so every patch that can have weight is
//   in those 27 cells: the light is continuous across cell planes (a Gaussian
//   cut off at the block's edge left visible seams on the bunny). A point with
//   no usable patch within one voxel looks once more with R = 2 in the
//   5 x 5 x 5 block around it; beyond that it stays black and is counted as
//   dark by the callers.
// * Normal agreement keeps walls meeting at a corner apart and makes the two
//   sides of a thin wall (opposite normals) ignore each other.
// * Visibility V: an occlusion ray from x to every patch that still has
//   weight, both ends offset a tenth of a voxel along their normals (to the
//   side each lights). Normal agreement alone is not enough: the floor under
//   a thin slab faces the same way as the slab's lit top less than a voxel
//   above it, and the floor on both sides of a wall standing on it is one
//   plane. Testing every patch, not only those of another normal cluster,
//   costs a few dozen rays per point and needs no threshold a scene could fall
//   on the wrong side of. The offsets keep a curved surface from hiding its
//   own patches: a patch centroid lies below a convex surface by the sagitta
//   (about s^2 / 8r for a patch of size s on curvature radius r), and a chord
//   of up to one voxel dips below it by as much; surfaces closer together
//   than a tenth of a voxel are below what the bake resolves anyway.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "patches/patch_set.h"
#include "raytrace/ray_tracer.h"
#include "runtime/transfer_grid.h"

namespace bounce {

struct GatherSettings {
  // Kernel radius in voxel units; at most 1 (the 27 searched cells hold
  // every patch within one voxel). 1 blends the ~3 patches per voxel of a
  // wall and its neighbours' without blurring light over more than a voxel.
  float radius_cells = 1.0f;
  int normal_power = 4;    // k in max(0, n . n_p)^k
  bool visibility = true;  // occlusion ray to each weighted patch
  // Ray end offsets along each end's normal, in voxel units (see above).
  float point_offset_cells = 0.1f;
  float patch_offset_cells = 0.1f;
  // Hits this close to the point (voxel units) do not block: a vertex on the
  // line where two walls meet lies in the other wall's plane, which an
  // offset along its own normal does not leave.
  float point_clearance_cells = 0.02f;
};

struct GatherResult {
  glm::vec3 light{0.0f};   // weighted mean of the patches' light; 0 when none counted
  float weight = 0.0f;     // sum of weights before normalising; 0 = dark
  bool widened = false;    // nothing usable within R: searched again with 2R
  std::uint32_t rays = 0;  // occlusion rays traced
};

class PatchGather {
 public:
  // `light` = light leaving each patch (exitance, one per patch); both are
  // copied (positions, normals and light, a few bytes per patch). `tracer`
  // must outlive the gather; it may be null only with settings.visibility
  // off. Throws bounce::Error when sizes differ or a light value is not
  // finite.
  PatchGather(const std::vector<Patch>& patches, const std::vector<glm::vec3>& light,
              const TransferGrid& grid, const RayTracer* tracer, GatherSettings settings);

  // Light at point x with unit normal n (the side that receives). Thread-safe.
  GatherResult gather(const glm::vec3& x, const glm::vec3& n) const;

  const TransferGrid& grid() const { return grid_; }
  const GatherSettings& settings() const { return settings_; }

 private:
  struct Candidate {
    std::uint32_t patch;
    float weight;
  };
  // Adds the patches of the cells on the shell `shell` cells around `c`
  // that lie within `reach` (voxel units) of x and face its way.
  void collect(const glm::vec3& x, const glm::vec3& n, const glm::ivec3& c, int shell, float reach,
               std::vector<Candidate>& out) const;
  std::uint64_t key(const glm::ivec3& c) const;

  std::vector<glm::vec3> position_, normal_, light_;  // per patch
  TransferGrid grid_;
  const RayTracer* tracer_;
  GatherSettings settings_;
  // Patches sorted by cell; cell key -> [first, first + count) in sorted_.
  std::vector<std::uint32_t> sorted_;
  std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> cells_;
};

}  // namespace bounce
