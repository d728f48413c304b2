#pragma once
// The ground truth the radiosity solver is measured against: a plain diffuse
// path tracer on the project's Embree BVH (raytrace/ray_tracer.h). It shares
// nothing with the solver beyond the scene and the ray tracer -- no voxels,
// patches, form factors, samples or runtime light functions -- so an error it
// reports is the solver's, not a shared approximation's. (Primary camera rays
// use runtime/camera_image.h's camera_ray_direction, which is camera geometry
// only, so reference and solver pictures line up pixel for pixel.)
//
// Units follow the solver's (docs/reference.md): irradiance E in W/m^2 per
// channel, radiosity B = albedo * E + emission (light leaving a surface), and
// pictures show B per pixel. "Indirect" is everything after the first
// bounce: E_indirect(x) is the irradiance x receives from light that was
// reflected at least once, the quantity the baked matrix T b delivers.
//
// Estimator: at a surface point x the path samples a cosine-weighted
// direction, so pi * L_in is an unbiased estimate of the irradiance, and the
// reflected radiance at the next hit y is albedo(y) * E(y) / pi. That gives
//   E_indirect(x) ~ albedo(y1) * (E_direct(y1) + albedo(y2) * (E_direct(y2) + ...))
// with E_direct at each vertex from two strategies for emissive triangles,
// combined by multiple importance sampling (Veach 1997, power heuristic):
// next-event estimation (one emissive triangle picked by power, one uniform
// point on it) and the emission the cosine-sampled bounce ray finds. NEE alone
// carries 1 / r^2 to nearby emitters, so a vertex near an edge of two
// emitting walls has variance ~ 1 / (distance to the edge)^2; path vertices
// land near edges with uniform density, so the indirect estimator had
// infinite variance: sample means came out low near edges (up to 20% at 4000
// paths, 5-12 reported standard errors) with a variance estimate that hid it. The MIS weights
// bound each strategy's contribution by the exitance. Point, spot and
// directional lights are deltas: NEE only, one shadow ray each. Russian
// roulette ends long paths without bias.
//
// Points exactly on an edge or corner (evaluation vertices) start on the
// plane of the neighbouring wall: shadow rays skip blockers within the
// offset, and a bounce ray that starts on the back of a wall moves off it and
// is cast again, so such points get the limit of their neighbourhood.
//
// Determinism: sample s of item i (pixel or point) draws from its own
// counter-based stream Rng(seed, i, s), and each item is accumulated in sample
// order by one thread, so results do not depend on the thread count.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "io/exr_writer.h"
#include "raytrace/ray_tracer.h"
#include "scene/scene.h"

namespace bounce {

struct ReferenceSettings {
  int samples = 256;       // paths per point or per pixel
  int min_bounces = 3;     // Russian roulette only after this many bounces
  int max_bounces = 1000;  // hard cap (a furnace of albedo 0.99 needs hundreds)
  std::uint64_t seed = 1;
  int threads = 0;  // 0: OpenMP's default

  // Throws bounce::Error naming the setting for values out of range.
  void validate() const;
};

// A surface point to estimate light at: position, the unit normal of the side
// that receives, and its albedo (for radiosity).
struct ReferencePoint {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  glm::vec3 albedo{0.0f};
  glm::vec3 emission{0.0f};
};

// Monte Carlo means with the variance of each mean (sample variance / n), per
// channel: a 3-sigma bound is 3 * sqrt(variance_of_mean).
struct PointReference {
  std::vector<glm::vec3> direct_irradiance;
  std::vector<glm::vec3> indirect_irradiance;
  std::vector<glm::vec3> indirect_variance;  // of the mean of indirect_irradiance
  std::vector<glm::vec3> radiosity;          // albedo * (direct + indirect) + emission
  std::vector<glm::vec3> radiosity_variance;
  int samples = 0;
};

struct ReferenceImages {
  RgbFloatImage full, indirect;
  RgbFloatImage full_variance, indirect_variance;  // of the pixel means
  std::vector<float> coverage;                     // share of rays that hit: 0 = background
  int samples = 0;
};

class ReferencePathTracer {
 public:
  ReferencePathTracer(const RayTracer& tracer, ReferenceSettings settings);

  // Irradiance and radiosity at the given points (`settings.samples` paths
  // each). Throws Cancelled when progress asks to stop.
  PointReference estimate_points(const std::vector<ReferencePoint>& points,
                                 Progress* progress = nullptr) const;

  const ReferenceSettings& settings() const { return settings_; }
  const RayTracer& tracer() const { return tracer_; }

 private:
  friend class ReferenceRenderer;
  struct Emitter {
    std::uint32_t triangle;
    glm::vec3 v0, e1, e2, normal, exitance;
    float area;
    bool two_sided;
  };
  class Sampler;
  // E_direct at x by NEE: delta lights in full, emissive triangles MIS-weighted
  // against the cosine-sampled bounce ray (which adds the rest, path()).
  glm::vec3 direct(const glm::vec3& x, const glm::vec3& n, Sampler& rng) const;
  // One path from x: returns the indirect irradiance and sets `direct_out` to
  // the direct irradiance at x (NEE plus what the first bounce ray finds).
  glm::vec3 path(const glm::vec3& x, const glm::vec3& n, Sampler& rng, glm::vec3& direct_out) const;
  // Solid-angle pdf with which direct() samples a point of `triangle` at
  // squared distance r2, seen under cos_y (0 for a non-emissive triangle).
  float light_pdf(std::uint32_t triangle, float r2, float cos_y) const;

  const RayTracer& tracer_;
  ReferenceSettings settings_;
  std::vector<Emitter> emitters_;
  std::vector<float> emitter_cdf_;    // by power (area x mean exitance)
  std::vector<float> triangle_pick_;  // per triangle: pick probability / area, 0 if not emissive
  float eps_ = 0.0f;
};

// Progressive camera pictures: add passes until the noise is low enough.
class ReferenceRenderer {
 public:
  // Throws bounce::Error for a size below 1 or above 16384.
  ReferenceRenderer(const ReferencePathTracer& pt, int width, int height);

  // `samples` more paths per pixel (samples seeded after the ones already
  // taken, so 2 x 64 equals 1 x 128 exactly). Throws Cancelled on a stop.
  void add_samples(int samples, Progress* progress = nullptr);
  int samples() const { return samples_; }
  // The current means, variances and coverage.
  ReferenceImages images() const;

 private:
  const ReferencePathTracer& pt_;
  int width_, height_;
  int samples_ = 0;
  // Per pixel and channel: sums of values and squares, in double so that
  // thousands of samples do not lose the variance to cancellation.
  std::vector<glm::dvec3> full_sum_, full_sq_, ind_sum_, ind_sq_;
  std::vector<std::uint32_t> hits_;
};

}  // namespace bounce
