#pragma once
// Error of light per mesh vertex (or per patch) against a reference at the
// same points. With x the test and y the reference radiosity, summed over
// vertices and channels:
//   relative RMSE  sqrt(sum (x - y)^2 / sum y^2)
//   mean relative  mean over vertices of |x - y| / max(|y|, floor), per channel
//                  (the floor, 5% of the mean reference, keeps vertices the
//                  reference sees nearly unlit from dominating)
//   max relative   the largest of those
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

struct VertexErrors {
  double relative_rmse = 0.0;
  double mean_relative = 0.0;
  double max_relative = 0.0;
  std::size_t vertices = 0;
};

// Throws bounce::Error when the sizes differ.
VertexErrors vertex_errors(const std::vector<glm::vec3>& test,
                           const std::vector<glm::vec3>& reference);

// Per vertex, the largest over channels of the relative error of
// vertex_errors (same floor): max_relative is the largest of them. Throws
// bounce::Error when the sizes differ.
std::vector<float> vertex_relative_errors(const std::vector<glm::vec3>& test,
                                          const std::vector<glm::vec3>& reference);

// sqrt(max(0, sum (x - y^)^2 - sum var) / sum y^2): the relative RMSE with
// the Monte Carlo reference's own noise (variance of each mean) removed, as
// for images (metrics/image_metrics.h). Throws bounce::Error on size mismatch.
double noise_corrected_relative_rmse(const std::vector<glm::vec3>& test,
                                     const std::vector<glm::vec3>& reference,
                                     const std::vector<glm::vec3>& reference_variance);

}  // namespace bounce
