#include "bake/camera_gather.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "base/error.h"
#include "patches/surface_patch_lookup.h"
#include "runtime/final_gather_build.h"
#include "runtime/patch_gather.h"
#include "transport/text_format.h"
#include "voxel/voxel_grid.h"

namespace bounce {

bool camera_gather_possible(const LoadedBake& bake) {
  if (bake.voxel_cells.empty() || bake.samples.carried.empty()) return false;
  for (const CarriedArea& piece : bake.samples.carried)
    if (piece.triangle == CarriedArea::kUnknownTriangle) return false;
  return true;
}

CameraGather::CameraGather(const RayTracer& tracer, const LoadedBake& bake,
                           const CameraImageSettings& settings, int rays, Progress* progress)
    : bake_(bake), tracer_(tracer) {
  if (!camera_gather_possible(bake))
    throw Error(bake.dir.string(),
                "does not say which triangle its surface pieces lie on (made "
                "by an older bounce): bake it again for gathered pictures");
  if (rays < 1) throw Error("camera gather", "needs at least one ray per pixel");
  // About 8 bytes per gather entry and up to one entry per ray: a picture
  // whose gather would not fit in memory is refused before any work.
  const double pixels = static_cast<double>(settings.width) * settings.height;
  if (pixels * rays > kMaxCameraGatherRays)
    throw Error(
        "camera gather",
        text_format("%dx%d pixels x %d rays is %.3g gather rays, more than %.3g: lower "
                    "the rays or the size, or gather from the nearest patches (0 rays)",
                    settings.width, settings.height, rays, pixels * rays, kMaxCameraGatherRays));
  const std::size_t triangles = tracer.scene().triangles.size();
  for (const CarriedArea& piece : bake.samples.carried)
    if (piece.triangle >= triangles)
      throw Error(bake.dir.string(), "names triangle " + std::to_string(piece.triangle) +
                                         " of a scene with " + std::to_string(triangles) +
                                         ": not this scene");
  const TransferGrid t = TransferGrid::from_manifest(bake.manifest);
  const VoxelGrid grid = VoxelGrid::restore(t.origin, t.cell_size, t.dims);
  const SurfacePatchLookup lookup(grid, bake.voxel_cells, bake.samples, bake.patch_of_sample);
  direct_ = render_camera_direct(tracer, settings, hits_, progress);
  std::vector<glm::vec3> positions, normals;
  positions.reserve(hits_.size());
  normals.reserve(hits_.size());
  for (const CameraHit& h : hits_) {
    positions.push_back(h.position);
    normals.push_back(h.normal);
  }
  // `rays` per pixel, shared by its n x n primary hits (at least 16 each),
  // so anti-aliasing does not multiply the gather's cost and memory.
  const int spp = std::max(1, settings.samples_per_side);
  FinalGatherSettings fg;
  fg.rays = std::max(16, rays / (spp * spp));
  fg.seed = settings.seed;
  gather_ = build_final_gather(tracer, lookup, bake.patches.patches, grid, positions, normals, fg,
                               progress);
  width_ = settings.width;
  height_ = settings.height;
  cell_size_ = grid.cell_size();
  const std::size_t pixel_count =
      static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  // render_camera_direct gives the hits in pixel order: each pixel's are a
  // contiguous run.
  pixel_first_.assign(pixel_count + 1, 0);
  for (const CameraHit& h : hits_) ++pixel_first_[h.pixel + 1];
  for (std::size_t p = 0; p < pixel_count; ++p) pixel_first_[p + 1] += pixel_first_[p];
}

std::vector<glm::vec3> CameraGather::filtered(const std::vector<glm::vec3>& irradiance) const {
  if (filter_radius_ <= 0) return irradiance;
  std::vector<glm::vec3> out(irradiance.size());
  // Hits farther apart than a quarter voxel, or whose normals differ by more
  // than about 25 degrees, barely mix: the gather's sources change over that
  // distance (the patches are a few per voxel), so its light may too.
  const float sigma = 0.25f * cell_size_;
  const float inv_two_sigma2 = 1.0f / (2.0f * sigma * sigma);
  const int r = filter_radius_;
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(hits_.size()); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const CameraHit& h = hits_[i];
    const int px = static_cast<int>(h.pixel % static_cast<std::uint32_t>(width_));
    const int py = static_cast<int>(h.pixel / static_cast<std::uint32_t>(width_));
    glm::vec3 sum(0.0f);
    float total = 0.0f;
    for (int y = std::max(0, py - r); y <= std::min(height_ - 1, py + r); ++y)
      for (int x = std::max(0, px - r); x <= std::min(width_ - 1, px + r); ++x) {
        const std::size_t q = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                              static_cast<std::size_t>(x);
        for (std::uint32_t k = pixel_first_[q]; k < pixel_first_[q + 1]; ++k) {
          const CameraHit& g = hits_[k];
          const float agree = glm::dot(h.normal, g.normal);
          if (agree < 0.9f) continue;
          const glm::vec3 d = g.position - h.position;
          const float w = std::exp(-glm::dot(d, d) * inv_two_sigma2) * agree * agree * agree;
          sum += w * irradiance[k];
          total += w;
        }
      }
    out[i] = total > 0.0f ? sum / total : irradiance[i];
  }
  return out;
}

CameraGather::~CameraGather() = default;

CameraImages CameraGather::images(const std::vector<glm::vec3>& first_hit,
                                  const std::vector<glm::vec3>& patch_indirect,
                                  const std::vector<glm::vec3>& sample_irradiance,
                                  const std::vector<Light>& lights,
                                  const std::vector<AreaLight>& area) const {
  const std::size_t n = bake_.size();
  if (first_hit.size() != n || patch_indirect.size() != n)
    throw Error("camera gather", "the light has " + std::to_string(patch_indirect.size()) +
                                     " patches, the bake " + std::to_string(n));
  std::vector<glm::vec3> reflected(n), gathered, sample_light;
  for (std::size_t p = 0; p < n; ++p) reflected[p] = first_hit[p] + patch_indirect[p];
  if (gather_.samples > 0)
    sample_light = sample_exitance(bake_.samples, bake_.patches, sample_irradiance, patch_indirect);
  gather_.irradiance(reflected, sample_light,
                     near_exitance(gather_.near, &tracer_, lights, area, patch_indirect), gathered);
  CameraImages images = direct_;
  add_indirect(images, hits_, filtered(gathered));
  return images;
}

}  // namespace bounce
