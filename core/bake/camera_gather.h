#pragma once
// Camera pictures of a bake read back, lit as the bake's vertices are: each
// pixel's primary hit gathers the light of the patches (and samples) it sees
// through ray-traced point-to-patch form factors (runtime/final_gather.h),
// instead of blending the nearest patches' light, which blurs it over a
// voxel (the foot of a sunlit pillar, the dark under an arch).
//
// The gather needs to know which patch stands for the point each gather ray
// hits: the bake folder's carried polygons with their triangles and sides,
// and its voxels' cells (SurfacePatchLookup). Bakes made before folders kept
// the triangles cannot: camera_gather_possible() says so.
//
// Built once per camera and bake (the rays); each frame is a sparse product
// of the patches' reflected light b + T b, as for the vertices.
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "folder/bake_reader.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_lights.h"
#include "runtime/camera_image.h"
#include "runtime/final_gather.h"

namespace bounce {

// Most gather rays one picture may ask for (pixels x rays per pixel): 2^30,
// about 8 GiB of gather entries at worst and minutes of tracing.
inline constexpr double kMaxCameraGatherRays = 1073741824.0;

// Whether `bake` keeps what a camera gather needs.
bool camera_gather_possible(const LoadedBake& bake);

class CameraGather {
 public:
  // Traces the camera's primary rays (direct light, shadowed, per pixel) and
  // `rays` gather rays per pixel from its hits (shared by its n x n
  // anti-aliasing hits, at least 16 each). Throws bounce::Error when pixels x
  // rays exceeds kMaxCameraGatherRays. Throws bounce::Error when the bake
  // cannot (camera_gather_possible) or its grid is malformed.
  CameraGather(const RayTracer& tracer, const LoadedBake& bake, const CameraImageSettings& settings,
               int rays, Progress* progress = nullptr);
  ~CameraGather();
  CameraGather(const CameraGather&) = delete;
  CameraGather& operator=(const CameraGather&) = delete;

  // The pictures with the indirect light of `patch_indirect` (T b per patch):
  // each hit gathers b + T b from the patches it sees and the first-hit light
  // of the samples it sees most (`sample_irradiance`: each sample's direct
  // irradiance of the same frame) and the near sources next to it, lit by
  // `lights` and `area` (the frame's), reflected with the hit's albedo.
  CameraImages images(const std::vector<glm::vec3>& first_hit,
                      const std::vector<glm::vec3>& patch_indirect,
                      const std::vector<glm::vec3>& sample_irradiance,
                      const std::vector<Light>& lights, const std::vector<AreaLight>& area) const;

  // Each hit's gathered irradiance is a Monte Carlo estimate: neighbouring
  // pixels' estimates of the same surface are averaged (an edge-aware filter
  // over `filter_radius` pixels, hits weighted by how near they lie in space,
  // within a quarter voxel, and how well their normals agree), which removes
  // most of the grain while edges, corners and contact shadows stay sharp.
  // 0 turns it off.
  void set_filter_radius(int pixels) { filter_radius_ = pixels; }

  std::size_t hits() const { return hits_.size(); }
  const FinalGather& gather() const { return gather_; }

 private:
  const LoadedBake& bake_;
  const RayTracer& tracer_;
  CameraImages direct_;
  std::vector<CameraHit> hits_;
  FinalGather gather_;
  int width_ = 0, height_ = 0;
  float cell_size_ = 1.0f;
  int filter_radius_ = 3;
  // Hits of pixel p: hits_[pixel_first_[p] .. pixel_first_[p + 1]).
  std::vector<std::uint32_t> pixel_first_;

  std::vector<glm::vec3> filtered(const std::vector<glm::vec3>& irradiance) const;
};

}  // namespace bounce
