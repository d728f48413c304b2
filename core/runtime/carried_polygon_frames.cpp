#include "runtime/carried_polygon_frames.h"

#include <algorithm>
#include <cstdint>

namespace bounce {

namespace {

CarriedPolygonFrame polygon_frame(const glm::vec3* poly, std::uint32_t count,
                                  const glm::vec3& side) {
  CarriedPolygonFrame f;
  if (count < 3) return f;
  const glm::vec3 v0 = poly[0];
  glm::vec3 twice_area(0.0f);
  for (std::uint32_t k = 1; k + 1 < count; ++k)
    twice_area += glm::cross(poly[k] - v0, poly[k + 1] - v0);
  const float twice = glm::length(twice_area);
  if (!(twice > 0.0f)) return f;
  f.normal = twice_area / twice;
  f.area = 0.5f * twice;
  glm::vec3 moment(0.0f);  // sum of fan triangles' (signed) areas x centroids
  for (std::uint32_t k = 1; k + 1 < count; ++k) {
    const glm::vec3 a = poly[k] - v0, b = poly[k + 1] - v0;
    moment += glm::dot(glm::cross(a, b), f.normal) * (a + b);
  }
  f.centroid = v0 + moment / (3.0f * twice);
  for (std::uint32_t k = 0; k < count; ++k) {
    const glm::vec3 d = poly[k] - f.centroid;
    f.radius2 = std::max(f.radius2, glm::dot(d, d));
  }
  // Oriented to the side the sample stands on (a part carried whole by a
  // sample of another triangle faces the sample's way, samples.cpp).
  if (glm::dot(f.normal, side) < 0.0f) f.normal = -f.normal;
  return f;
}

}  // namespace

std::vector<CarriedPolygonFrame> carried_polygon_frames(const SampleSet& samples) {
  std::vector<CarriedPolygonFrame> frames;
  if (samples.carried_first.size() != samples.samples.size() + 1) return frames;
  frames.resize(samples.carried.size());
  const auto sample_count = static_cast<std::int64_t>(samples.samples.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t si = 0; si < sample_count; ++si) {
    const auto s = static_cast<std::size_t>(si);
    for (std::uint32_t c = samples.carried_first[s]; c < samples.carried_first[s + 1]; ++c) {
      const CarriedArea& piece = samples.carried[c];
      frames[c] = polygon_frame(&samples.carried_vertices[piece.first_vertex], piece.vertex_count,
                                samples.samples[s].normal);
    }
  }
  return frames;
}

}  // namespace bounce
