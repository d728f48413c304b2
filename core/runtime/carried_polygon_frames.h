#pragma once
// The plane, area, centroid and extent of every polygon the samples carry
// (SampleSet::carried), what direct light from point and spot lights needs
// of each polygon besides its vertices. They depend on the geometry only:
// a caller that lights the same samples frame after frame (RuntimeFrame)
// computes them once instead of at every frame, where they were most of the
// cost of a point light on finely meshed surfaces (cornell-bunny: ~10
// polygons per sample).
#include <vector>

#include <glm/glm.hpp>

#include "patches/samples.h"

namespace bounce {

// In float, relative to the polygon's first vertex (the polygons are small;
// absolute coordinates would cancel).
struct CarriedPolygonFrame {
  glm::vec3 normal{0.0f};    // unit, the side its sample stands on
  glm::vec3 centroid{0.0f};  // area centroid
  float area = 0.0f;         // 0: degenerate (fewer than 3 vertices or no area), skipped
  float radius2 = 0.0f;      // largest squared distance of a vertex from the centroid
};

// One frame per entry of samples.carried, in the same order; empty when the
// samples carry no polygons (a bake folder without them).
std::vector<CarriedPolygonFrame> carried_polygon_frames(const SampleSet& samples);

}  // namespace bounce
