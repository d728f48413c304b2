#include "metrics/error_heat_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/error.h"
#include "compress/matrix_picture.h"

namespace bounce {

namespace {

void check_sizes(const RgbFloatImage& test, const RgbFloatImage& reference) {
  if (test.width != reference.width || test.height != reference.height)
    throw Error("error picture", "the two images differ in size");
}

}  // namespace

RgbFloatImage absolute_difference(const RgbFloatImage& test, const RgbFloatImage& reference) {
  check_sizes(test, reference);
  RgbFloatImage out(test.width, test.height);
  for (std::size_t k = 0; k < out.pixels.size(); ++k)
    out.pixels[k] = glm::abs(test.pixels[k] - reference.pixels[k]);
  return out;
}

Rgb8Image relative_error_heat_map(const RgbFloatImage& test, const RgbFloatImage& reference,
                                  const std::vector<float>& coverage, double full_scale) {
  check_sizes(test, reference);
  if (coverage.size() != test.pixels.size())
    throw Error("error picture", "the coverage does not match the images");
  if (!(full_scale > 0.0)) throw Error("error picture", "the full scale must be above 0");
  double sum = 0.0;
  std::size_t seen = 0;
  for (std::size_t k = 0; k < reference.pixels.size(); ++k)
    if (coverage[k] > 0.0f) {
      sum += glm::length(glm::dvec3(reference.pixels[k]));
      ++seen;
    }
  const double floor = std::max(seen > 0 ? 0.05 * sum / static_cast<double>(seen) : 0.0,
                                std::numeric_limits<double>::min());
  Rgb8Image out(test.width, test.height);
  for (int y = 0; y < test.height; ++y)
    for (int x = 0; x < test.width; ++x) {
      const std::size_t k = test.index(x, y);
      if (!(coverage[k] > 0.0f)) continue;  // background stays black
      const double e = glm::length(glm::dvec3(test.pixels[k]) - glm::dvec3(reference.pixels[k])) /
                       std::max(glm::length(glm::dvec3(reference.pixels[k])), floor);
      colormap(std::min(1.0, e / full_scale), out.at(x, y));
    }
  return out;
}

}  // namespace bounce
