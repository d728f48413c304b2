#pragma once
// n cosine-distributed directions about a surface normal, evenly spread: a
// Fibonacci lattice on the unit disk (point i at radius sqrt((i + 1/2) / n),
// angle 2 pi i / golden ratio) lifted to the hemisphere. Projecting the
// hemisphere onto its base disk turns uniform density on the disk into
// cosine density on the hemisphere, so the share of the directions that
// reach a surface estimates the form factor to it, with the low noise of a
// stratified pattern. Each caller turns the lattice by its own angle so that
// neighbouring points do not share their directions.
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

class CosineLattice {
 public:
  explicit CosineLattice(std::size_t n) : disk_(n) {
    for (std::size_t i = 0; i < n; ++i) {
      const double r = std::sqrt((static_cast<double>(i) + 0.5) / static_cast<double>(n));
      const double phi = 2.0 * std::numbers::pi * static_cast<double>(i) / std::numbers::phi;
      disk_[i] = {static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi))};
    }
  }

  std::size_t size() const { return disk_.size(); }

  // A frame about unit normal n: tangents t, b and the turn of the lattice
  // (an angle in radians).
  struct Frame {
    glm::vec3 t, b, n;
    float cos_turn, sin_turn;
    Frame(const glm::vec3& normal, float turn)
        : n(normal), cos_turn(std::cos(turn)), sin_turn(std::sin(turn)) {
      const glm::vec3 a = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
      t = glm::normalize(glm::cross(a, n));
      b = glm::cross(n, t);
    }
  };

  // Direction k of the lattice in `frame`.
  glm::vec3 direction(std::size_t k, const Frame& frame) const {
    const glm::vec2 p = disk_[k];
    const glm::vec2 d(frame.cos_turn * p.x - frame.sin_turn * p.y,
                      frame.sin_turn * p.x + frame.cos_turn * p.y);
    const float z = std::sqrt(std::max(0.0f, 1.0f - glm::dot(d, d)));
    return d.x * frame.t + d.y * frame.b + z * frame.n;
  }

 private:
  std::vector<glm::vec2> disk_;
};

}  // namespace bounce
