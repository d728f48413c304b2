#pragma once
// The classic runtime baseline: no precomputed multi-bounce matrix, just the
// form factors and K gathering iterations per frame,
//   y = sum_(h=1..K) M^h b,  M = diag(rho_c) F,
// K matrix-vector products per colour channel. What the published precomputed-radiosity
// method compares its one-product runtime against.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

class ClassicRadiosity {
 public:
  // `form_factors`: n x n row-major (F[p * n + q], gathering: row p receives
  // from q as in the bake's F.npy); `albedo` per patch; `bounces` = K >= 1.
  ClassicRadiosity(std::vector<float> form_factors, std::vector<glm::vec3> albedo, int bounces);

  // indirect = sum_(h=1..K) M^h b per colour channel; allocates nothing
  // after the first call (one call at a time per object).
  void multiply(const std::vector<glm::vec3>& b, std::vector<glm::vec3>& indirect) const;

  std::size_t size() const { return n_; }
  int bounces() const { return bounces_; }
  // Bytes one update reads: F once per bounce and channel.
  std::size_t bytes_per_update() const {
    return 3 * static_cast<std::size_t>(bounces_) * n_ * n_ * sizeof(float);
  }

 private:
  std::size_t n_;
  std::vector<float> f_;
  std::vector<glm::vec3> albedo_;
  int bounces_;
  mutable std::vector<float> v_, w_;
};

}  // namespace bounce
