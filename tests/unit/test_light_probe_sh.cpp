// The light probes' SH L2 fit (runtime/light_probes.h) against environments
// whose irradiance is known in closed form: an irradiance of order 2 or less
// is reproduced exactly; a uniform sky over one hemisphere, whose irradiance
// pi (1 + n.y) / 2 is of order 1, too; a directional light, whose clamped
// cosine has terms of every even order, comes within the error any L2
// irradiance has for it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "runtime/light_probes.h"

namespace bounce {
namespace {

constexpr double kPi = std::numbers::pi;

// n evenly spread unit directions (a Fibonacci sphere).
std::vector<glm::vec3> sphere(int n) {
  std::vector<glm::vec3> d;
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(1.0 - z * z);
    const double phi = 2.0 * kPi * i / std::numbers::phi;
    d.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  return d;
}

// The fitted SH of one probe whose directions receive e(direction).
template <typename F>
std::vector<glm::vec3> fit(F e) {
  std::vector<glm::vec3> at;
  for (const glm::vec3& d : probe_directions()) at.push_back(e(d));
  std::vector<glm::vec3> sh;
  fit_probe_sh(at, sh);
  return sh;
}

TEST(LightProbeSh, BasisIsOrthonormalOverTheSphere) {
  const std::vector<glm::vec3> dirs = sphere(20000);
  for (std::size_t i = 0; i < kShCoefficients; ++i)
    for (std::size_t j = 0; j < kShCoefficients; ++j) {
      double sum = 0.0;
      for (const glm::vec3& d : dirs) sum += sh_basis(d)[i] * sh_basis(d)[j];
      EXPECT_NEAR(4.0 * kPi * sum / static_cast<double>(dirs.size()), i == j ? 1.0 : 0.0, 2e-3)
          << i << ", " << j;
    }
}

TEST(LightProbeSh, AnIrradianceOfOrderTwoIsFittedExactly) {
  const auto e = [](const glm::vec3& n) {
    const float v = 2.0f + 0.5f * n.x - 0.3f * n.y + 0.2f * n.z + 0.4f * n.x * n.y -
                    0.25f * (3.0f * n.z * n.z - 1.0f) + 0.1f * (n.x * n.x - n.y * n.y);
    return glm::vec3(v, 2.0f * v, 0.5f * v);
  };
  const std::vector<glm::vec3> sh = fit(e);
  for (const glm::vec3& n : sphere(500)) {
    const glm::vec3 want = e(n), got = sh_irradiance(sh.data(), n);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-5f * want[c] + 1e-5f);
  }
}

TEST(LightProbeSh, AUniformSkyGivesItsClosedFormCoefficients) {
  // Radiance 1 from every direction with y > 0: E(n) = pi (1 + n.y) / 2, so
  // c_0 = (pi / 2) / 0.282095 and c_1 (the y term) = (pi / 2) / 0.488603,
  // every other coefficient 0.
  const auto e = [](const glm::vec3& n) {
    return glm::vec3(static_cast<float>(kPi * (1.0 + n.y) / 2.0));
  };
  const std::vector<glm::vec3> sh = fit(e);
  EXPECT_NEAR(sh[0].r, kPi / 2.0 / 0.282095, 1e-5);
  EXPECT_NEAR(sh[1].r, kPi / 2.0 / 0.488603, 1e-5);
  for (std::size_t j = 2; j < kShCoefficients; ++j) EXPECT_NEAR(sh[j].r, 0.0, 1e-5) << j;
}

// A directional light of unit irradiance from `a`: E(n) = max(0, n.a), the
// sharpest irradiance there is. Its L2 projection c_lm = A_l Y_lm(a)
// (A = pi, 2 pi / 3, pi / 4) leaves an RMS error of 0.036 over the sphere,
// what every L2 irradiance has for it. The fit from 14 directions also sees
// the orders above 2 at its directions: over 300 random light directions
// its RMS error was 1.29 times the projection's on average and 1.79 times at
// worst (26 directions, the cube's edges added: 1.18 at worst, for 1.9
// times the rays and entries; indirect light is much smoother than a
// directional light, so 14 it is). Within twice the projection's error.
TEST(LightProbeSh, ADirectionalLightIsFittedAsCloseAsItsProjection) {
  const double a_l[kShCoefficients] = {kPi,     2 * kPi / 3, 2 * kPi / 3, 2 * kPi / 3, kPi / 4,
                                       kPi / 4, kPi / 4,     kPi / 4,     kPi / 4};
  for (const glm::vec3 a : {glm::vec3(0, 1, 0), glm::normalize(glm::vec3(0.3f, -0.8f, 0.5f)),
                            glm::normalize(glm::vec3(1, 1, 1))}) {
    const auto e = [&a](const glm::vec3& n) { return glm::vec3(std::max(0.0f, glm::dot(n, a))); };
    const std::vector<glm::vec3> sh = fit(e);
    std::vector<glm::vec3> projected(kShCoefficients);
    const auto y = sh_basis(a);
    for (std::size_t j = 0; j < kShCoefficients; ++j)
      projected[j] = glm::vec3(static_cast<float>(a_l[j] * y[j]));
    double fit_sq = 0.0, projection_sq = 0.0;
    const std::vector<glm::vec3> dirs = sphere(4000);
    for (const glm::vec3& n : dirs) {
      const double want = e(n).r;
      fit_sq += std::pow(sh_irradiance(sh.data(), n).r - want, 2.0);
      projection_sq += std::pow(sh_irradiance(projected.data(), n).r - want, 2.0);
    }
    const double fit_rms = std::sqrt(fit_sq / static_cast<double>(dirs.size()));
    const double projection_rms = std::sqrt(projection_sq / static_cast<double>(dirs.size()));
    std::printf(
        "light from (%.2f, %.2f, %.2f): RMS error of the fit %.4f, of the projection %.4f\n", a.x,
        a.y, a.z, fit_rms, projection_rms);
    EXPECT_LT(fit_rms, 2.0 * projection_rms);
  }
}

}  // namespace
}  // namespace bounce
