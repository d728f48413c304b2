#include "metrics/vertex_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/error.h"

namespace bounce {

namespace {

void check_sizes(const std::vector<glm::vec3>& test, const std::vector<glm::vec3>& reference) {
  if (test.size() != reference.size())
    throw Error("vertex metrics", "the test has " + std::to_string(test.size()) +
                                      " vertices, the reference " +
                                      std::to_string(reference.size()));
}

// 5% of the reference's mean |value| per channel: the denominator's floor.
double relative_floor(const std::vector<glm::vec3>& reference) {
  double ref_sum = 0.0;
  for (const glm::vec3& y : reference)
    for (int c = 0; c < 3; ++c) ref_sum += std::abs(static_cast<double>(y[c]));
  return std::max(0.05 * ref_sum / (3.0 * static_cast<double>(reference.size())),
                  std::numeric_limits<double>::min());
}

}  // namespace

std::vector<float> vertex_relative_errors(const std::vector<glm::vec3>& test,
                                          const std::vector<glm::vec3>& reference) {
  check_sizes(test, reference);
  std::vector<float> out(test.size(), 0.0f);
  if (test.empty()) return out;
  const double floor = relative_floor(reference);
  for (std::size_t i = 0; i < test.size(); ++i) {
    double worst = 0.0;
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(static_cast<double>(test[i][c]) - reference[i][c]) /
                                  std::max(std::abs(static_cast<double>(reference[i][c])), floor));
    out[i] = static_cast<float>(worst);
  }
  return out;
}

VertexErrors vertex_errors(const std::vector<glm::vec3>& test,
                           const std::vector<glm::vec3>& reference) {
  check_sizes(test, reference);
  VertexErrors e;
  e.vertices = test.size();
  if (test.empty()) return e;
  double sq = 0.0, ref_sq = 0.0;
  for (std::size_t i = 0; i < test.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(test[i][c]) - reference[i][c];
      sq += d * d;
      ref_sq += static_cast<double>(reference[i][c]) * reference[i][c];
    }
  e.relative_rmse = ref_sq > 0.0 ? std::sqrt(sq / ref_sq)
                                 : (sq > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  const double floor = relative_floor(reference);
  double sum = 0.0;
  for (std::size_t i = 0; i < test.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double r = std::abs(static_cast<double>(test[i][c]) - reference[i][c]) /
                       std::max(std::abs(static_cast<double>(reference[i][c])), floor);
      sum += r;
      e.max_relative = std::max(e.max_relative, r);
    }
  e.mean_relative = sum / (3.0 * static_cast<double>(test.size()));
  return e;
}

double noise_corrected_relative_rmse(const std::vector<glm::vec3>& test,
                                     const std::vector<glm::vec3>& reference,
                                     const std::vector<glm::vec3>& reference_variance) {
  if (test.size() != reference.size() || reference_variance.size() != reference.size())
    throw Error("vertex metrics", "test, reference and variance differ in size");
  double sq = 0.0, var = 0.0, ref_sq = 0.0;
  for (std::size_t i = 0; i < test.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(test[i][c]) - reference[i][c];
      sq += d * d;
      var += reference_variance[i][c];
      ref_sq += static_cast<double>(reference[i][c]) * reference[i][c];
    }
  if (!(ref_sq > 0.0)) return std::numeric_limits<double>::infinity();
  return std::sqrt(std::max(0.0, sq - var) / ref_sq);
}

}  // namespace bounce
