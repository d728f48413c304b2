#include "runtime/camera_image.h"

#include <cmath>

#include "base/error.h"
#include "base/random.h"
#include "io/png_writer.h"
#include "io/tone_map.h"
#include "runtime/area_lights.h"
#include "runtime/direct_light.h"

namespace bounce {

namespace {

struct CameraFrame {
  glm::vec3 forward, right, up;
  float tan_half_y, aspect;
};

CameraFrame frame_of(const Camera& camera, int width, int height) {
  const glm::vec3 view = camera.target - camera.position;
  if (!(glm::length(view) > 0.0f)) throw Error("camera", "target equals position");
  CameraFrame f;
  f.forward = glm::normalize(view);
  const glm::vec3 right = glm::cross(f.forward, camera.up);
  if (!(glm::length(right) > 1e-6f)) throw Error("camera", "up is parallel to the view direction");
  f.right = glm::normalize(right);
  f.up = glm::cross(f.right, f.forward);
  if (!(camera.fov_y_deg > 0.0f && camera.fov_y_deg < 180.0f))
    throw Error("camera", "fov_y_deg must be in (0, 180)");
  f.tan_half_y = std::tan(0.5f * glm::radians(camera.fov_y_deg));
  f.aspect = static_cast<float>(width) / static_cast<float>(height);
  return f;
}

glm::vec3 direction(const CameraFrame& f, int width, int height, float x, float y) {
  const float u = (2.0f * x / static_cast<float>(width) - 1.0f) * f.tan_half_y * f.aspect;
  const float v = (1.0f - 2.0f * y / static_cast<float>(height)) * f.tan_half_y;
  return glm::normalize(f.forward + u * f.right + v * f.up);
}

}  // namespace

glm::vec3 camera_ray_direction(const Camera& camera, int width, int height, float x, float y) {
  return direction(frame_of(camera, width, height), width, height, x, y);
}

namespace {

// Traces the camera's primary rays and fills the direct image, the coverage
// and the counts; at every hit that receives light, gather(p, normal, albedo,
// pixel) returns the indirect light there (a negative red channel: none found).
template <class Gather>
CameraImages trace_camera(const RayTracer& tracer, const CameraImageSettings& settings,
                          Progress* progress, Gather&& gather) {
  constexpr int kMaxSize = 16384;
  if (settings.width < 1 || settings.height < 1 || settings.width > kMaxSize ||
      settings.height > kMaxSize)
    throw Error("camera image", "size must be 1.." + std::to_string(kMaxSize) + " per side");
  if (settings.samples_per_side < 1 || settings.samples_per_side > 16)
    throw Error("camera image", "samples per side must be 1..16");
  if (settings.area_light_strata < 1 || settings.area_light_strata > 64)
    throw Error("camera image", "area light strata must be 1..64");
  const Scene& scene = tracer.scene();
  const CameraFrame frame = frame_of(scene.camera, settings.width, settings.height);
  const std::vector<AreaLight> area = area_lights(scene);
  const std::vector<Light>& lights = settings.lights ? *settings.lights : scene.lights;
  const int n = settings.samples_per_side;
  const float inv_samples = 1.0f / static_cast<float>(n * n);

  CameraImages out;
  out.direct = RgbFloatImage(settings.width, settings.height);
  out.indirect = out.direct;
  out.full = out.direct;
  out.coverage.assign(out.direct.pixels.size(), 0.0f);
  std::size_t hit_pixels = 0, dark = 0, back = 0;
  if (progress != nullptr)
    progress->begin_stage("camera image", static_cast<std::size_t>(settings.height));
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : hit_pixels, dark, back)
  for (int y = 0; y < settings.height; ++y) {
    if (progress != nullptr && progress->should_stop()) continue;
    for (int x = 0; x < settings.width; ++x) {
      const std::size_t pixel = out.direct.index(x, y);
      Rng rng(settings.seed, pixel);
      glm::vec3 direct(0.0f), gathered(0.0f);
      int hits = 0;
      for (int sy = 0; sy < n; ++sy)
        for (int sx = 0; sx < n; ++sx) {
          // One ray: the pixel centre; more: jittered strata of the pixel.
          const float jx =
              n == 1 ? 0.5f : (static_cast<float>(sx) + rng.uniform()) / static_cast<float>(n);
          const float jy =
              n == 1 ? 0.5f : (static_cast<float>(sy) + rng.uniform()) / static_cast<float>(n);
          const glm::vec3 dir = direction(frame, settings.width, settings.height,
                                          static_cast<float>(x) + jx, static_cast<float>(y) + jy);
          const Hit hit = tracer.intersect(scene.camera.position, dir);
          if (!hit.hit) continue;
          ++hits;
          glm::vec3 normal = hit.geometric_normal;
          if (glm::dot(normal, dir) > 0.0f) {
            // The back of a one-sided triangle neither receives nor emits.
            if (!scene.two_sided(hit.triangle)) {
              ++back;
              continue;
            }
            normal = -normal;
          }
          const glm::vec3 p = scene.camera.position + hit.t * dir;
          // The texel under the pixel's ray: the picture shows the texture.
          const glm::vec3 albedo = scene.albedo_at(hit.triangle, p);
          direct +=
              albedo * irradiance_at(tracer, p, normal, lights, area, settings.area_light_strata,
                                     pixel * static_cast<std::uint64_t>(n * n) +
                                         static_cast<std::uint64_t>(sy * n + sx));
          if (settings.show_emission) direct += scene.emission_at(hit.triangle, p);
          const glm::vec3 g = gather(p, normal, albedo, pixel);
          if (g.r < 0.0f)
            ++dark;
          else
            gathered += g;
        }
      if (hits == 0) continue;  // background stays exactly zero
      ++hit_pixels;
      out.coverage[pixel] = static_cast<float>(hits) * inv_samples;
      out.direct.pixels[pixel] = direct * inv_samples;
      out.indirect.pixels[pixel] = gathered * inv_samples;
      out.full.pixels[pixel] = out.direct.pixels[pixel] + out.indirect.pixels[pixel];
    }
    if (progress != nullptr) progress->advance();
  }
  if (progress != nullptr) {
    progress->check();
    progress->end_stage();
  }
  out.hit_pixels = hit_pixels;
  out.dark_hits = dark;
  out.back_hits = back;
  return out;
}

}  // namespace

CameraImages render_camera(const RayTracer& tracer, const PatchGather& indirect,
                           const CameraImageSettings& settings, Progress* progress) {
  return trace_camera(tracer, settings, progress,
                      [&](const glm::vec3& p, const glm::vec3& n, const glm::vec3&, std::size_t) {
                        const GatherResult g = indirect.gather(p, n);
                        return g.weight > 0.0f ? g.light : glm::vec3(-1.0f);
                      });
}

CameraImages render_camera_direct(const RayTracer& tracer, const CameraImageSettings& settings,
                                  std::vector<CameraHit>& hits, Progress* progress) {
  const int spp = settings.samples_per_side * settings.samples_per_side;
  std::vector<std::vector<CameraHit>> per_row(static_cast<std::size_t>(settings.height));
  CameraImages images = trace_camera(
      tracer, settings, progress,
      [&](const glm::vec3& p, const glm::vec3& n, const glm::vec3& albedo, std::size_t pixel) {
        const auto row = pixel / static_cast<std::size_t>(settings.width);
        per_row[row].push_back(
            {p, n, albedo / static_cast<float>(spp), static_cast<std::uint32_t>(pixel)});
        return glm::vec3(0.0f);
      });
  hits.clear();
  for (const auto& row : per_row) hits.insert(hits.end(), row.begin(), row.end());
  return images;
}

void add_indirect(CameraImages& images, const std::vector<CameraHit>& hits,
                  const std::vector<glm::vec3>& irradiance) {
  if (irradiance.size() != hits.size())
    throw Error("camera image", "one irradiance per camera hit expected");
  for (std::size_t i = 0; i < hits.size(); ++i) {
    const glm::vec3 light = hits[i].weight * irradiance[i];
    images.indirect.pixels[hits[i].pixel] += light;
    images.full.pixels[hits[i].pixel] += light;
  }
}

float write_camera_images(const CameraImages& images, const std::filesystem::path& dir,
                          const std::string& stem) {
  std::vector<float> lum;
  for (std::size_t p = 0; p < images.full.pixels.size(); ++p)
    if (images.coverage[p] > 0.0f) lum.push_back(luminance(images.full.pixels[p]));
  const float exposure = ToneMap::exposure_for(std::move(lum));
  const std::pair<const char*, const RgbFloatImage*> parts[] = {
      {"direct", &images.direct}, {"indirect", &images.indirect}, {"full", &images.full}};
  for (const auto& [name, image] : parts) {
    const std::string base = stem + "_" + name;
    write_exr(dir / (base + ".exr"), *image);
    Rgb8Image png(image->width, image->height);
    for (int y = 0; y < image->height; ++y)
      for (int x = 0; x < image->width; ++x)
        for (int c = 0; c < 3; ++c) png.at(x, y)[c] = ToneMap::srgb8(exposure * image->at(x, y)[c]);
    write_png(dir / (base + ".png"), png);
  }
  return exposure;
}

}  // namespace bounce
