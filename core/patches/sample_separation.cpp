#include "patches/sample_separation.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace bounce {

namespace {

// Pairs tested: samples of one surface, facing within 26 degrees of each
// other and each within a tenth of their distance of the other's plane.
// Their test segment is lifted off the surface by 0.15 of their distance:
// between two points whose normals differ by 26 degrees, a convex surface
// (a crease or a curve) bulges above their chord by less than 0.12 of its
// length, so the segment passes over it.
constexpr float kSameFacing = 0.9f;
constexpr float kPlaneShare = 0.1f;
constexpr float kLift = 0.15f;

bool on_one_surface(const Sample& x, const Sample& y, float distance) {
  if (glm::dot(x.normal, y.normal) < kSameFacing) return false;
  const glm::vec3 d = y.position - x.position;
  return std::abs(glm::dot(d, x.normal)) <= kPlaneShare * distance &&
         std::abs(glm::dot(d, y.normal)) <= kPlaneShare * distance;
}

bool faces_opposite_ways(const SampleSet& set, std::uint32_t first, std::uint32_t end) {
  for (std::uint32_t a = first; a < end; ++a)
    for (std::uint32_t b = a + 1; b < end; ++b)
      if (glm::dot(set.samples[a].normal, set.samples[b].normal) < 0.0f) return true;
  return false;
}

}  // namespace

SampleSeparation::SampleSeparation(const RayTracer& tracer, const SampleSet& set,
                                   std::size_t voxel) {
  const std::uint32_t first = set.first[voxel], end = set.first[voxel + 1];
  if (!faces_opposite_ways(set, first, end)) return;
  const std::size_t n = end - first;
  const float eps = 10.0f * tracer.epsilon();
  std::vector<ShadowRay> rays;
  std::vector<std::uint32_t> pair_of;  // a * n + b of each ray
  for (std::uint32_t a = 0; a < n; ++a)
    for (std::uint32_t b = a + 1; b < n; ++b) {
      const Sample& x = set.samples[first + a];
      const Sample& y = set.samples[first + b];
      const float distance = glm::distance(x.position, y.position);
      if (!on_one_surface(x, y, distance)) continue;
      const float lift = eps + kLift * distance;
      const glm::vec3 from = x.position + lift * x.normal;
      const glm::vec3 to = y.position + lift * y.normal;
      rays.push_back({from, to - from, 0.0f, 1.0f});
      pair_of.push_back(a * static_cast<std::uint32_t>(n) + b);
    }
  rays_ = rays.size();
  std::vector<std::uint8_t> blocked(rays.size());
  tracer.occluded(rays.data(), rays.size(), blocked.data());
  words_ = (n + 63) / 64;
  bits_.assign(n * words_, 0);
  for (std::size_t k = 0; k < rays.size(); ++k) {
    if (!blocked[k]) continue;
    const std::size_t a = pair_of[k] / n, b = pair_of[k] % n;
    bits_[a * words_ + b / 64] |= std::uint64_t{1} << (b % 64);
    bits_[b * words_ + a / 64] |= std::uint64_t{1} << (a % 64);
    ++separated_pairs_;
  }
}

}  // namespace bounce
