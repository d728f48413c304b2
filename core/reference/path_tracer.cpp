#include "reference/path_tracer.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "base/error.h"
#include "base/random.h"
#include "runtime/camera_image.h"
#include "scene/texture.h"

namespace bounce {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

float max_component(const glm::vec3& v) { return std::max(v.r, std::max(v.g, v.b)); }

// Orthonormal basis around a unit normal (Duff et al. 2017, "Building an
// orthonormal basis, revisited"): no branch on a nearly parallel axis.
void basis(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

int thread_count(const ReferenceSettings& s) {
  return s.threads > 0 ? s.threads : omp_get_max_threads();
}

}  // namespace

// Sample s of item i: its own stream, whatever thread runs it.
class ReferencePathTracer::Sampler {
 public:
  Sampler(std::uint64_t seed, std::uint64_t item, std::uint64_t sample)
      : rng_(splitmix64(seed + 0x632BE59BD9B4E019ull * (sample + 1)), item) {}
  float uniform() { return rng_.uniform(); }

 private:
  Rng rng_;
};

void ReferenceSettings::validate() const {
  if (samples < 1 || samples > 1'000'000)
    throw Error("reference samples",
                "must be between 1 and 1000000, got " + std::to_string(samples));
  if (min_bounces < 0 || max_bounces < 1 || min_bounces > max_bounces)
    throw Error("reference bounces", "need 0 <= min_bounces <= max_bounces and max_bounces >= 1");
  if (threads < 0) throw Error("reference threads", "must be >= 0 (0 = all cores)");
}

ReferencePathTracer::ReferencePathTracer(const RayTracer& tracer, ReferenceSettings settings)
    : tracer_(tracer), settings_(settings), eps_(10.0f * tracer.epsilon()) {
  settings_.validate();
  const Scene& scene = tracer.scene();
  float total = 0.0f;
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    const Material& m = scene.material_of(t);
    if (!m.is_emissive()) continue;
    const glm::vec3 cross = scene.triangle_cross(t);
    const float len = glm::length(cross);
    if (!(len > 0.0f)) continue;  // degenerate: emits nothing
    Emitter e{};
    e.triangle = static_cast<std::uint32_t>(t);
    e.v0 = scene.vertex(t, 0);
    e.e1 = scene.vertex(t, 1) - e.v0;
    e.e2 = scene.vertex(t, 2) - e.v0;
    e.normal = cross / len;
    e.exitance = m.emission;
    // A textured emitter is picked by its own triangle's power (the
    // texture's mean over it); where it emits is looked up per point.
    if (scene.emission_textured(t))
      e.exitance = m.emission_factor * m.emission_texture->mean_over_triangle(scene.triangle_uv[t]);
    e.area = 0.5f * len;
    e.two_sided = scene.two_sided(t);
    emitters_.push_back(e);
    total += e.area * (e.exitance.r + e.exitance.g + e.exitance.b) * (e.two_sided ? 2.0f : 1.0f);
    emitter_cdf_.push_back(total);
  }
  if (!(total > 0.0f)) {
    // Only textured emitters whose triangles' texels are all black: nothing
    // for next-event estimation to pick (bounce rays still find any light).
    emitters_.clear();
    emitter_cdf_.clear();
  }
  for (float& c : emitter_cdf_) c /= total;
  triangle_pick_.assign(scene.triangle_count(), 0.0f);
  for (std::size_t k = 0; k < emitters_.size(); ++k)
    triangle_pick_[emitters_[k].triangle] =
        (emitter_cdf_[k] - (k > 0 ? emitter_cdf_[k - 1] : 0.0f)) / emitters_[k].area;
}

float ReferencePathTracer::light_pdf(std::uint32_t triangle, float r2, float cos_y) const {
  const float pick = triangle_pick_[triangle];
  if (!(pick > 0.0f) || !(cos_y > 0.0f)) return 0.0f;
  return pick * r2 / cos_y;
}

glm::vec3 ReferencePathTracer::direct(const glm::vec3& x, const glm::vec3& n, Sampler& rng) const {
  const glm::vec3 origin = x + eps_ * n;
  // Shadow rays ignore blockers within eps_ of the origin: a point on an edge
  // lies in the plane of the neighbouring wall, which would block every ray at
  // t = 0 (no blocker can really sit closer than the offset itself).
  const auto blocked = [&](const glm::vec3& d, float t_far) {
    return tracer_.occluded(origin, d, eps_ / glm::length(d), t_far);
  };
  glm::vec3 e(0.0f);
  for (const Light& light : tracer_.scene().lights) {
    if (light.type == Light::Type::Directional) {
      const glm::vec3 to_light = -glm::normalize(light.direction);
      const float cos_x = glm::dot(n, to_light);
      if (cos_x <= 0.0f || blocked(to_light, std::numeric_limits<float>::infinity())) continue;
      e += light.color * light.intensity * cos_x;
      continue;
    }
    const glm::vec3 d = light.position - origin;
    const float r2 = glm::dot(d, d);
    if (!(r2 > 0.0f)) continue;
    const glm::vec3 dir = d / std::sqrt(r2);
    const float cos_x = glm::dot(n, dir);
    if (cos_x <= 0.0f) continue;
    float cone = 1.0f;
    if (light.type == Light::Type::Spot) {
      // Smoothstep between the inner and outer half-angles (docs/scene-format.md).
      const float c = glm::dot(-dir, glm::normalize(light.direction));
      const float inner = std::cos(glm::radians(light.spot_inner_deg));
      const float outer = std::cos(glm::radians(light.spot_outer_deg));
      const float s = std::clamp((c - outer) / std::max(1e-6f, inner - outer), 0.0f, 1.0f);
      cone = s * s * (3.0f - 2.0f * s);
      if (cone <= 0.0f) continue;
    }
    if (blocked(d, 1.0f - 1e-4f)) continue;
    e += light.color * light.intensity * cone * cos_x / r2;
  }
  if (emitters_.empty()) return e;
  // One emissive triangle, picked in proportion to its power, one uniform
  // point on it: E = (M / pi) cos_x cos_y / r^2 * area / P(triangle).
  const float u = rng.uniform();
  const auto k = static_cast<std::size_t>(std::min<std::ptrdiff_t>(
      std::lower_bound(emitter_cdf_.begin(), emitter_cdf_.end(), u) - emitter_cdf_.begin(),
      static_cast<std::ptrdiff_t>(emitters_.size()) - 1));
  const float pick = emitter_cdf_[k] - (k > 0 ? emitter_cdf_[k - 1] : 0.0f);
  const Emitter& em = emitters_[k];
  float a = rng.uniform(), b = rng.uniform();
  if (a + b > 1.0f) {
    a = 1.0f - a;
    b = 1.0f - b;
  }
  const glm::vec3 y = em.v0 + a * em.e1 + b * em.e2;
  const glm::vec3 d = y - origin;
  const float r2 = glm::dot(d, d);
  if (!(r2 > 0.0f) || !(pick > 0.0f)) return e;
  const glm::vec3 dir = d / std::sqrt(r2);
  const float cos_x = glm::dot(n, dir);
  float cos_y = -glm::dot(em.normal, dir);
  if (em.two_sided) cos_y = std::abs(cos_y);
  if (cos_x <= 0.0f || cos_y <= 0.0f) return e;
  if (blocked(d, 1.0f - 1e-4f)) return e;
  // MIS, power heuristic: (L cos_x / p_l) * p_l^2 / (p_l^2 + p_b^2) with the
  // solid-angle pdfs p_l of this sample and p_b = cos_x / pi of the bounce
  // ray. Bounded by M / 2 however close the emitter is.
  const float p_l = light_pdf(em.triangle, r2, cos_y), p_b = cos_x / kPi;
  const glm::vec3 exitance = tracer_.scene().emission_textured(em.triangle)
                                 ? tracer_.scene().emission_at(em.triangle, y)
                                 : em.exitance;
  return e + exitance * (cos_x / kPi * p_l / (p_l * p_l + p_b * p_b));
}

glm::vec3 ReferencePathTracer::path(const glm::vec3& x, const glm::vec3& n, Sampler& rng,
                                    glm::vec3& direct_out) const {
  const Scene& scene = tracer_.scene();
  direct_out = direct(x, n, rng);
  glm::vec3 e(0.0f), throughput(1.0f), pos = x, normal = n;
  for (int bounce = 1; bounce <= settings_.max_bounces; ++bounce) {
    // Cosine-weighted direction: pdf cos / pi, so pi * L_in estimates E.
    const float u1 = rng.uniform(), u2 = rng.uniform();
    const float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
    glm::vec3 t, b;
    basis(normal, t, b);
    const glm::vec3 dir = glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * b +
                                         std::sqrt(std::max(0.0f, 1.0f - u1)) * normal);
    glm::vec3 origin = pos + eps_ * normal;
    Hit hit = tracer_.intersect(origin, dir);
    // A ray that starts on the back of a wall within the offset (a point on an
    // edge or corner lies in its neighbours' planes) is not blocked by it: move
    // off that plane to its front, where the ray goes, and cast again. A front
    // face at t ~ 0 stays a hit: it is the neighbouring wall, seen at the edge.
    for (int retry = 0;
         retry < 3 && hit.hit && hit.t <= eps_ && glm::dot(hit.geometric_normal, dir) > 0.0f &&
         !scene.two_sided(hit.triangle);
         ++retry) {
      origin += eps_ * hit.geometric_normal;
      hit = tracer_.intersect(origin, dir);
    }
    if (!hit.hit) break;
    glm::vec3 ng = hit.geometric_normal;
    if (glm::dot(ng, dir) > 0.0f) {
      if (!scene.two_sided(hit.triangle)) break;  // the back of a one-sided wall sends nothing
      ng = -ng;
    }
    const Material& m = scene.material_of(hit.triangle);
    // The emission this ray finds is the other MIS half of E_direct at the
    // vertex it left: weight p_b^2 / (p_b^2 + p_l^2); pi * L / p_b = M.
    if (m.is_emissive()) {
      const float p_b = glm::dot(normal, dir) / kPi;
      const float p_l = light_pdf(hit.triangle, hit.t * hit.t, -glm::dot(ng, dir));
      // p_l = 0 where NEE cannot sample (a wall seen edge-on): all to this ray.
      const float w = p_l > 0.0f ? p_b * p_b / (p_b * p_b + p_l * p_l) : 1.0f;
      const glm::vec3 found = scene.emission_at(hit.triangle, origin + hit.t * dir) * w;
      if (bounce == 1)
        direct_out += found;
      else
        e += throughput * found;
    }
    // The texel where the ray landed: the bake's samples average the same
    // texture over their surface, so both sides see the same albedo on average.
    throughput *= scene.albedo_at(hit.triangle, origin + hit.t * dir);
    if (max_component(throughput) <= 0.0f) break;
    // Roulette before the vertex's E_direct, not after: both MIS halves (NEE
    // here, the emission the next ray finds) must survive or die together.
    if (bounce > settings_.min_bounces) {
      const float survive = std::min(1.0f, max_component(throughput));
      if (rng.uniform() >= survive) break;
      throughput /= survive;
    }
    pos = origin + hit.t * dir;
    normal = ng;
    e += throughput * direct(pos, normal, rng);
  }
  return e;
}

PointReference ReferencePathTracer::estimate_points(const std::vector<ReferencePoint>& points,
                                                    Progress* progress) const {
  const std::size_t count = points.size();
  PointReference out;
  out.samples = settings_.samples;
  out.direct_irradiance.assign(count, glm::vec3(0.0f));
  out.indirect_irradiance.assign(count, glm::vec3(0.0f));
  out.indirect_variance.assign(count, glm::vec3(0.0f));
  out.radiosity.assign(count, glm::vec3(0.0f));
  out.radiosity_variance.assign(count, glm::vec3(0.0f));
  if (progress) progress->begin_stage("reference points", std::max<std::size_t>(1, count));
  const auto n = static_cast<double>(settings_.samples);
#pragma omp parallel for schedule(dynamic, 8) num_threads(thread_count(settings_))
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(count); ++ii) {
    if (progress && progress->should_stop()) continue;
    const auto i = static_cast<std::size_t>(ii);
    const ReferencePoint& p = points[i];
    glm::dvec3 dsum(0.0), isum(0.0), isq(0.0), bsum(0.0), bsq(0.0);
    for (int s = 0; s < settings_.samples; ++s) {
      Sampler rng(settings_.seed, i, static_cast<std::uint64_t>(s));
      glm::vec3 direct_x;
      const glm::dvec3 ind(path(p.position, p.normal, rng, direct_x));
      const glm::dvec3 d(direct_x);
      const glm::dvec3 b = glm::dvec3(p.albedo) * (d + ind) + glm::dvec3(p.emission);
      dsum += d;
      isum += ind;
      isq += ind * ind;
      bsum += b;
      bsq += b * b;
    }
    const auto variance_of_mean = [n](const glm::dvec3& sum, const glm::dvec3& sq) {
      if (n < 2.0) return glm::vec3(0.0f);
      const glm::dvec3 mean = sum / n;
      return glm::vec3(glm::max(sq / n - mean * mean, glm::dvec3(0.0)) / (n - 1.0));
    };
    out.direct_irradiance[i] = glm::vec3(dsum / n);
    out.indirect_irradiance[i] = glm::vec3(isum / n);
    out.indirect_variance[i] = variance_of_mean(isum, isq);
    out.radiosity[i] = glm::vec3(bsum / n);
    out.radiosity_variance[i] = variance_of_mean(bsum, bsq);
    if (progress) progress->advance();
  }
  if (progress) {
    progress->check();
    progress->end_stage();
  }
  return out;
}

ReferenceRenderer::ReferenceRenderer(const ReferencePathTracer& pt, int width, int height)
    : pt_(pt), width_(width), height_(height) {
  if (width < 1 || width > 16384 || height < 1 || height > 16384)
    throw Error("reference image size", "width and height must be between 1 and 16384");
  const auto count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  full_sum_.assign(count, glm::dvec3(0.0));
  full_sq_ = ind_sum_ = ind_sq_ = full_sum_;
  hits_.assign(count, 0);
}

void ReferenceRenderer::add_samples(int samples, Progress* progress) {
  if (samples < 1) throw Error("reference samples", "a pass needs at least one sample per pixel");
  const Scene& scene = pt_.tracer_.scene();
  const glm::vec3 eye = scene.camera.position;
  // Fails early, with the camera's own message, for a degenerate camera.
  (void)camera_ray_direction(scene.camera, width_, height_, 0.5f, 0.5f);
  if (progress) progress->begin_stage("reference image", static_cast<std::size_t>(height_));
  const int first = samples_;
#pragma omp parallel for schedule(dynamic, 1) num_threads(thread_count(pt_.settings_))
  for (int y = 0; y < height_; ++y) {
    if (progress && progress->should_stop()) continue;
    for (int x = 0; x < width_; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                            static_cast<std::size_t>(x);
      for (int s = first; s < first + samples; ++s) {
        ReferencePathTracer::Sampler rng(pt_.settings_.seed, i, static_cast<std::uint64_t>(s));
        const float jx = rng.uniform(), jy = rng.uniform();
        const glm::vec3 dir = camera_ray_direction(
            scene.camera, width_, height_, static_cast<float>(x) + jx, static_cast<float>(y) + jy);
        const Hit hit = pt_.tracer_.intersect(eye, dir);
        if (!hit.hit) continue;  // background: contributes zero, coverage tells
        ++hits_[i];
        glm::vec3 ng = hit.geometric_normal;
        if (glm::dot(ng, dir) > 0.0f) {
          if (!scene.two_sided(hit.triangle)) continue;  // back of a one-sided wall: dark
          ng = -ng;
        }
        const glm::vec3 p = eye + hit.t * dir;
        const glm::dvec3 albedo(scene.albedo_at(hit.triangle, p));
        glm::vec3 direct_p;
        const glm::dvec3 ind(pt_.path(p, ng, rng, direct_p));
        const glm::dvec3 d(direct_p);
        const glm::dvec3 indirect_b = albedo * ind;
        const glm::dvec3 full_b =
            albedo * d + indirect_b + glm::dvec3(scene.emission_at(hit.triangle, p));
        full_sum_[i] += full_b;
        full_sq_[i] += full_b * full_b;
        ind_sum_[i] += indirect_b;
        ind_sq_[i] += indirect_b * indirect_b;
      }
    }
    if (progress) progress->advance();
  }
  if (progress) {
    progress->check();
    progress->end_stage();
  }
  samples_ += samples;
}

ReferenceImages ReferenceRenderer::images() const {
  ReferenceImages out;
  out.samples = samples_;
  out.full = out.indirect = out.full_variance = out.indirect_variance =
      RgbFloatImage(width_, height_);
  out.coverage.assign(full_sum_.size(), 0.0f);
  if (samples_ == 0) return out;
  const auto n = static_cast<double>(samples_);
  for (std::size_t i = 0; i < full_sum_.size(); ++i) {
    const glm::dvec3 fm = full_sum_[i] / n, im = ind_sum_[i] / n;
    out.full.pixels[i] = glm::vec3(fm);
    out.indirect.pixels[i] = glm::vec3(im);
    if (n >= 2.0) {
      out.full_variance.pixels[i] =
          glm::vec3(glm::max(full_sq_[i] / n - fm * fm, glm::dvec3(0.0)) / (n - 1.0));
      out.indirect_variance.pixels[i] =
          glm::vec3(glm::max(ind_sq_[i] / n - im * im, glm::dvec3(0.0)) / (n - 1.0));
    }
    out.coverage[i] = static_cast<float>(hits_[i]) / static_cast<float>(samples_);
  }
  return out;
}

}  // namespace bounce
