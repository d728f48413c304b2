#include "reference_check.h"

#include <chrono>
#include <cstdio>

#include "metrics/image_metrics.h"
#include "raytrace/ray_tracer.h"
#include "reference/reference_cache.h"
#include "runtime/camera_image.h"

namespace bounce::cli {

nlohmann::json check_bake_against_reference(const Scene& scene, const BakeResult& bake,
                                            Progress& progress, std::string& line) {
  using Clock = std::chrono::steady_clock;
  constexpr int kWidth = 96, kHeight = 72;
  const RayTracer tracer(scene);
  ReferenceSettings rs;
  rs.samples = 256;
  const ReferencePathTracer pt(tracer, rs);
  const ReferenceCache cache(ReferenceCache::default_dir());
  auto t = Clock::now();
  bool cached = false;
  const ReferenceImages ref =
      cached_reference_images(pt, kWidth, kHeight, &cache, &progress, &cached);
  const double reference_seconds = std::chrono::duration<double>(Clock::now() - t).count();
  const std::vector<std::uint8_t> mask = mask_from_coverage(ref.coverage);

  std::shared_ptr<void> keep;
  const IndirectMultiply multiply = baked_multiply(bake.transport, bake.storage, keep);
  const PatchLighting light =
      light_patches(tracer, bake.samples, bake.patches, scene.lights, area_lights(scene), multiply);
  const double update_ms = 1e3 * (light.seconds_direct + light.seconds_indirect);
  const PatchGather gather(bake.patches.patches, light.indirect,
                           TransferGrid::from(bake.voxels.grid), &tracer, GatherSettings{});
  CameraImageSettings cs;
  cs.width = kWidth;
  cs.height = kHeight;
  cs.samples_per_side = 2;
  const CameraImages images = render_camera(tracer, gather, cs, &progress);
  const double error =
      noise_corrected_relative_rmse(images.indirect, ref.indirect, ref.indirect_variance, mask);
  double var = 0.0, sq = 0.0;
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i])
      for (int c = 0; c < 3; ++c) {
        var += ref.indirect_variance.pixels[i][c];
        sq += static_cast<double>(ref.indirect.pixels[i][c]) * ref.indirect.pixels[i][c];
      }
  const double noise = sq > 0.0 ? std::sqrt(var / sq) : 0.0;
  char text[512];
  std::snprintf(text, sizeof text,
                "Against the path-traced reference (%dx%d, %d paths per pixel%s): indirect light "
                "relative RMSE %.3f (noise-corrected; the reference's own noise %.3f), bake "
                "%.2f s, one light update %.2f ms",
                kWidth, kHeight, ref.samples, cached ? ", cached" : "", error, noise,
                bake.total_seconds, update_ms);
  line = text;
  return {{"indirect_relative_rmse", error},
          {"reference_noise", noise},
          {"reference_samples", ref.samples},
          {"reference_cached", cached},
          {"reference_seconds", reference_seconds},
          {"bake_seconds", bake.total_seconds},
          {"update_ms", update_ms}};
}

}  // namespace bounce::cli
