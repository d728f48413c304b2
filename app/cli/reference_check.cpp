#include "reference_check.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>

#include "bounce/metrics.h"
#include "bounce/relight.h"
#include "bounce/report.h"

namespace bounce::cli {

namespace {

// The light probes' SH of the same frame against the path tracer at up to
// kProbes probes, six axis normals each, with 4096 paths per point and
// normal: a reference noise of about 5% on the Cornell box.
nlohmann::json check_probes(const RayTracer& tracer, const BakeResult& bake,
                            const Relighter& relighter, Progress& progress, std::string& line) {
  constexpr std::size_t kProbes = 64;
  std::vector<glm::vec3> irradiance, sh;
  const auto start = std::chrono::steady_clock::now();
  relighter.gather_far(bake.light_probes.gather, irradiance);
  fit_probe_sh(irradiance, sh);
  const double ms =
      1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ReferenceSettings rs;
  rs.samples = 4096;
  const ReferencePathTracer pt(tracer, rs);
  const ProbeReferenceError e =
      probe_reference_error(pt, bake.light_probes.position, sh, kProbes, &progress);
  char text[320];
  std::snprintf(text, sizeof text,
                "\nLight probes (%zu, %zu measured, six axis normals, %d paths each): relative "
                "RMSE %.3f (noise-corrected %.3f; the reference's own noise %.3f), mean level "
                "%.3f of the reference's, SH of every probe %.2f ms",
                bake.light_probes.size(), e.probes_measured, e.samples, e.relative_rmse,
                e.noise_corrected_rmse, e.reference_noise, e.level, ms);
  line += text;
  return {{"probes", bake.light_probes.size()},
          {"probes_measured", e.probes_measured},
          {"reference_samples", e.samples},
          {"relative_rmse", e.relative_rmse},
          {"noise_corrected_rmse", e.noise_corrected_rmse},
          {"reference_noise", e.reference_noise},
          {"mean_level", e.level},
          {"sh_ms", ms}};
}

}  // namespace

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

  // The product bounce solve picks on a CPU, one frame of the scene's lights.
  RelighterSettings relight;
  relight.multiply = MultiplyChoice::kAutoCpu;
  relight.frame.record = false;
  Relighter relighter(tracer, bake.samples, bake.patches,
                      stored_transport(bake.transport, bake.storage), relight);
  // Best of three frames: the first also pages in the frame's buffers.
  const std::vector<AreaLight> area = area_lights(scene);
  double update_seconds = std::numeric_limits<double>::infinity();
  for (int frame = 0; frame < 3; ++frame) {
    relighter.light(scene.lights, area);
    double seconds = 0.0;
    for (const double s : relighter.frame().pass_seconds()) seconds += s;
    update_seconds = std::min(update_seconds, seconds);
  }
  const double update_ms = 1e3 * update_seconds;
  // The rest of a light move: the bake's gather to its lit mesh's vertices
  // (their near sources lit, then the sparse product), best of three frames.
  const std::size_t vertices = bake.vertex_gather.points();
  double gather_ms = 0.0;
  if (vertices > 0) {
    std::vector<glm::vec3> vertex_irradiance;
    gather_ms = std::numeric_limits<double>::infinity();
    for (int frame = 0; frame < 3; ++frame) {
      const auto start = Clock::now();
      relighter.gather(bake.vertex_gather, vertex_irradiance);
      gather_ms =
          std::min(gather_ms, 1e3 * std::chrono::duration<double>(Clock::now() - start).count());
    }
  }
  // Each pixel's indirect light by the final gather from the patches it sees
  // (runtime/final_gather.h), as bounce solve shows it.
  CameraImageSettings cs;
  cs.width = kWidth;
  cs.height = kHeight;
  cs.samples_per_side = 2;
  std::vector<CameraHit> hits;
  CameraImages images = render_camera_direct(tracer, cs, hits, &progress);
  std::vector<glm::vec3> positions, normals, irradiance;
  for (const CameraHit& h : hits) {
    positions.push_back(h.position);
    normals.push_back(h.normal);
  }
  const SurfacePatchLookup lookup(bake.voxels, bake.samples, bake.patch_of_sample);
  relighter.gather(build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid,
                                      positions, normals, {}, &progress),
                   irradiance);
  add_indirect(images, hits, irradiance);
  const double error =
      noise_corrected_relative_rmse(images.indirect, ref.indirect, ref.indirect_variance, mask);
  double var = 0.0, sq = 0.0, mean = 0.0, ref_mean = 0.0;
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i])
      for (int c = 0; c < 3; ++c) {
        var += ref.indirect_variance.pixels[i][c];
        sq += static_cast<double>(ref.indirect.pixels[i][c]) * ref.indirect.pixels[i][c];
        mean += images.indirect.pixels[i][c];
        ref_mean += ref.indirect.pixels[i][c];
      }
  const double noise = sq > 0.0 ? std::sqrt(var / sq) : 0.0;
  const double level = ref_mean > 0.0 ? mean / ref_mean : 0.0;
  char text[640];
  std::snprintf(text, sizeof text,
                "Against the path-traced reference (%dx%d, %d paths per pixel%s): indirect light "
                "relative RMSE %.3f (noise-corrected; the reference's own noise %.3f), mean "
                "level %.3f of the reference's, bake %.2f s, one light update %.2f ms",
                kWidth, kHeight, ref.samples, cached ? ", cached" : "", error, noise, level,
                bake.total_seconds, update_ms + gather_ms);
  line = text;
  if (vertices > 0) {
    std::snprintf(text, sizeof text,
                  " (direct light and T b %.2f ms, the gather to the lit mesh's %zu vertices "
                  "%.2f ms, %s loop)",
                  update_ms, vertices, gather_ms,
                  bake.vertex_gather.compact_loop.empty()
                      ? "float-row"
                      : bake.vertex_gather.compact_loop.c_str());
    line += text;
  }
  nlohmann::json result = {{"indirect_relative_rmse", error},
                           {"indirect_mean_level", level},
                           {"transfer", "final gather"},
                           {"reference_noise", noise},
                           {"reference_samples", ref.samples},
                           {"reference_cached", cached},
                           {"reference_seconds", reference_seconds},
                           {"bake_seconds", bake.total_seconds},
                           {"update_ms", update_ms},
                           {"gather_vertices", vertices},
                           {"gather_ms", gather_ms},
                           {"gather_loop", bake.vertex_gather.compact_loop},
                           {"light_move_ms", update_ms + gather_ms}};
  if (bake.light_probes.size() > 0)
    result["light_probes"] = check_probes(tracer, bake, relighter, progress, line);
  return result;
}

}  // namespace bounce::cli
