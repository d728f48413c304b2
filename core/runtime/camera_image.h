#pragma once
// Pictures of the lit scene from the scene's camera, the way a real-time
// renderer would show the baked light: one primary Embree ray per pixel (or
// n x n jittered ones), and at the hit
//   direct   = albedo x direct irradiance (point, spot, directional and area
//              lights, shadow rays; runtime/direct_light.h), computed exactly
//              per pixel, plus the emitter's own exitance where it is seen;
//   indirect = the patches' indirect light gathered at the hit point with the
//              hit's normal (runtime/patch_gather.h, the same function that
//              lights mesh vertices);
//   full     = direct + indirect.
// Pixels whose rays all miss are background: exactly zero in all three.
//
// The gather must hold the *indirect* light per patch (T b), not b + T b:
// the first hit is what the direct image computes exactly per pixel.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "io/exr_writer.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_lights.h"
#include "runtime/patch_gather.h"
#include "scene/scene.h"

namespace bounce {

struct CameraImageSettings {
  int width = 640;
  int height = 480;
  // n x n jittered primary rays per pixel; 1 = one ray through the centre.
  int samples_per_side = 1;
  int area_light_strata = kAreaStrata;  // as the bake's direct light of emissive triangles
  bool show_emission = true;  // emitters seen by the camera show their exitance (direct image)
  std::uint64_t seed = 1;     // jitter of pixels and area-light samples
  // The point, spot and directional lights of the direct image; unset: the
  // scene's own. A lighting session that moved its lights passes them here.
  std::optional<std::vector<Light>> lights;
};

struct CameraImages {
  RgbFloatImage direct, indirect, full;
  // Share of each pixel's primary rays that hit the scene: 0 = background.
  std::vector<float> coverage;
  std::size_t hit_pixels = 0;
  std::size_t dark_hits = 0;  // primary hits where the gather found no patch
  std::size_t back_hits = 0;  // primary hits on the unlit back of a one-sided triangle
};

// Unit direction of the primary ray through image point (x, y), in pixels
// from the top-left corner (the centre of pixel (i, j) is (i + 0.5, j + 0.5)).
// Throws bounce::Error for a camera whose target is its position or whose up
// is parallel to the view direction.
glm::vec3 camera_ray_direction(const Camera& camera, int width, int height, float x, float y);

// Renders tracer.scene()'s camera. Throws bounce::Error for a size below 1 or
// above 16384, Cancelled when progress asks to stop.
CameraImages render_camera(const RayTracer& tracer, const PatchGather& indirect,
                           const CameraImageSettings& settings, Progress* progress = nullptr);

// Where the camera sees surface that receives light: a primary ray's hit,
// its receiving side's normal, and its pixel with the weight its light
// takes there (albedo / rays per pixel).
struct CameraHit {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec3 weight;
  std::uint32_t pixel;
};

// The direct image, coverage and counts of render_camera, with an indirect
// image of zeros; `hits` gets every primary hit (in pixel order), for an
// indirect light computed at those points and added by add_indirect.
CameraImages render_camera_direct(const RayTracer& tracer, const CameraImageSettings& settings,
                                  std::vector<CameraHit>& hits, Progress* progress = nullptr);

// Adds weight x irradiance[i] at each hit's pixel to the indirect and full
// images (runtime/final_gather.h gives the irradiance).
void add_indirect(CameraImages& images, const std::vector<CameraHit>& hits,
                  const std::vector<glm::vec3>& irradiance);

// Writes <stem>_direct, <stem>_indirect, <stem>_full as .exr (linear float)
// and .png (io/tone_map.h: one exposure for all three, from the full image's
// hit pixels, so the three pictures add up as the light does). Returns the
// exposure.
float write_camera_images(const CameraImages& images, const std::filesystem::path& dir,
                          const std::string& stem);

}  // namespace bounce
