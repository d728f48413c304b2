#include "runtime/light_probes.h"

#include <cmath>
#include <cstdint>
#include <utility>

#include "base/error.h"

namespace bounce {

namespace {

using FitMatrix = std::array<std::array<float, kProbeDirections>, kShCoefficients>;

std::array<glm::vec3, kProbeDirections> make_directions() {
  std::array<glm::vec3, kProbeDirections> d{};
  for (int axis = 0; axis < 3; ++axis) {
    d[2 * axis][axis] = 1.0f;
    d[2 * axis + 1][axis] = -1.0f;
  }
  const float s = 1.0f / std::sqrt(3.0f);
  for (int c = 0; c < 8; ++c)
    d[6 + c] = s * glm::vec3(c & 1 ? -1.0f : 1.0f, c & 2 ? -1.0f : 1.0f, c & 4 ? -1.0f : 1.0f);
  return d;
}

// (Y^T Y)^-1 Y^T by Gauss-Jordan elimination in double: Y^T Y is 9 x 9 and
// well conditioned for these directions (they are symmetric under the
// cube's rotations), so no pivoting beyond the largest in its column.
FitMatrix make_fit_matrix() {
  const auto& dirs = probe_directions();
  constexpr std::size_t n = kShCoefficients, k = kProbeDirections;
  std::array<std::array<double, k>, n> yt{};  // Y^T
  for (std::size_t i = 0; i < k; ++i) {
    const auto y = sh_basis(dirs[i]);
    for (std::size_t j = 0; j < n; ++j) yt[j][i] = y[j];
  }
  std::array<std::array<double, n>, n> a{};
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t c = 0; c < n; ++c)
      for (std::size_t i = 0; i < k; ++i) a[r][c] += yt[r][i] * yt[c][i];
  auto rhs = yt;
  for (std::size_t col = 0; col < n; ++col) {
    std::size_t pivot = col;
    for (std::size_t r = col + 1; r < n; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    if (std::abs(a[pivot][col]) < 1e-9)
      throw Error("light probes", "the probe directions do not determine SH L2");
    std::swap(a[col], a[pivot]);
    std::swap(rhs[col], rhs[pivot]);
    for (std::size_t r = 0; r < n; ++r) {
      if (r == col) continue;
      const double f = a[r][col] / a[col][col];
      for (std::size_t c = 0; c < n; ++c) a[r][c] -= f * a[col][c];
      for (std::size_t i = 0; i < k; ++i) rhs[r][i] -= f * rhs[col][i];
    }
  }
  FitMatrix m{};
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t i = 0; i < k; ++i) m[r][i] = static_cast<float>(rhs[r][i] / a[r][r]);
  return m;
}

}  // namespace

const std::array<glm::vec3, kProbeDirections>& probe_directions() {
  static const std::array<glm::vec3, kProbeDirections> directions = make_directions();
  return directions;
}

std::array<float, kShCoefficients> sh_basis(const glm::vec3& n) {
  const float x = n.x, y = n.y, z = n.z;
  return {0.282095f,
          0.488603f * y,
          0.488603f * z,
          0.488603f * x,
          1.092548f * x * y,
          1.092548f * y * z,
          0.315392f * (3.0f * z * z - 1.0f),
          1.092548f * x * z,
          0.546274f * (x * x - y * y)};
}

glm::vec3 sh_irradiance(const glm::vec3* sh, const glm::vec3& n) {
  const auto y = sh_basis(n);
  glm::vec3 e(0.0f);
  for (std::size_t j = 0; j < kShCoefficients; ++j) e += y[j] * sh[j];
  return e;
}

const FitMatrix& sh_fit_matrix() {
  static const FitMatrix matrix = make_fit_matrix();
  return matrix;
}

void fit_probe_sh(const std::vector<glm::vec3>& direction_irradiance, std::vector<glm::vec3>& sh) {
  if (direction_irradiance.size() % kProbeDirections != 0)
    throw Error("light probes", "irradiance for " + std::to_string(direction_irradiance.size()) +
                                    " directions is not a whole number of probes");
  const std::size_t probes = direction_irradiance.size() / kProbeDirections;
  const FitMatrix& m = sh_fit_matrix();
  sh.resize(probes * kShCoefficients);
#pragma omp parallel for schedule(static, 256)
  for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(probes); ++pi) {
    const auto p = static_cast<std::size_t>(pi);
    const glm::vec3* e = direction_irradiance.data() + p * kProbeDirections;
    for (std::size_t j = 0; j < kShCoefficients; ++j) {
      glm::vec3 c(0.0f);
      for (std::size_t k = 0; k < kProbeDirections; ++k) c += m[j][k] * e[k];
      sh[p * kShCoefficients + j] = c;
    }
  }
}

}  // namespace bounce
