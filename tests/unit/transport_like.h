#pragma once
// A test matrix shaped like a transport matrix, shared by the codec tests.
#include <cmath>
#include <random>
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

// Light exchange between random points on three walls of a box, in random
// order (like patches in voxel order): smooth in space, unordered in index.
inline std::vector<float> transport_like(std::size_t n, float scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec3> p(n);
  for (auto& x : p) {
    const int wall = static_cast<int>(u(rng) * 3.0f);
    x = wall == 0   ? glm::vec3(u(rng), u(rng), 0.0f)
        : wall == 1 ? glm::vec3(0.0f, u(rng), u(rng))
                    : glm::vec3(u(rng), 0.0f, u(rng));
  }
  std::vector<float> t(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      t[i * n + j] = i == j ? 0.0f
                            : scale * 0.01f * std::exp(-glm::length(p[i] - p[j]) / 0.15f) *
                                  (1.0f + 0.1f * u(rng));
  return t;
}

}  // namespace bounce
