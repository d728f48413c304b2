#pragma once
// Light probes: points in the empty space next to surfaces that light what
// moves through the scene (a character, a prop) with the same live solution
// as the walls around them. Each frame a probe holds its irradiance as
// spherical harmonics of order 2 (SH L2, 9 coefficients per colour channel).
//
// A probe is gathered as kProbeDirections points at its position, one per
// fixed direction (the 6 axes and the 8 cube diagonals), each a final-gather
// point (runtime/final_gather.h) whose cosine rays cover the hemisphere about
// its direction: the 14 hemispheres together cover the whole sphere, the
// rows are the vertices' kind (the same patch, cluster and sample sources,
// seen weights, no leak through walls), and a frame is the same sparse
// product. Each frame the 14 irradiances are fitted with the 9 SH
// coefficients by least squares, a fixed 9 x 14 matrix. Projecting each ray
// onto the 9 basis functions at bake time instead would store 9 weights per
// source where the directions store one per source and direction, with the
// same rays; and the fitted coefficients reproduce the gathered irradiance
// of the axis directions an engine's checks use, where a projection of
// cosine rays would need its own quadrature of the sphere. Why 14: for the
// sharpest irradiance there is, a directional light's clamped cosine, the
// fit's RMS error over the sphere is 1.29 times (at worst 1.79 times) that
// of the exact L2 projection, against 1.18 at worst with the 12 cube edges
// added (26 directions, 1.9 times the rays and entries); bounced light is
// far smoother, and on the Cornell box the 14 come within 0.065 of the
// path tracer at the axis normals (tests/unit/test_light_probes.cpp).
//
// The SH convention (docs/bake-format.md, "Light probes"):
//   - the real SH basis, orthonormal over the sphere, in the order
//     (l, m) = (0,0), (1,-1), (1,0), (1,1), (2,-2), (2,-1), (2,0), (2,1), (2,2):
//       Y0 = 0.282095,
//       Y1 = 0.488603 y, Y2 = 0.488603 z, Y3 = 0.488603 x,
//       Y4 = 1.092548 xy, Y5 = 1.092548 yz, Y6 = 0.315392 (3z^2 - 1),
//       Y7 = 1.092548 xz, Y8 = 0.546274 (x^2 - y^2),
//     with (x, y, z) the unit normal in the scene's own axes;
//   - the coefficients c_j are of IRRADIANCE: E(n) = sum_j c_j Y_j(n) is the
//     irradiance (W/m^2) a surface with normal n receives at the probe, from
//     light reflected at least once (b + T b, the quantity the vertices'
//     gather sums), plus the emissive surfaces' light when the caller adds
//     it (LightingSession does); a Lambertian surface of albedo a sends out
//     a E(n) / pi radiance. The direct light of the scene's point, spot and
//     directional lights is not in it: it stays with the engine's own
//     lights, as the vertices' is computed apart;
//   - radiance coefficients (three.js's SphericalHarmonics3 / LightProbe,
//     Unity's SphericalHarmonicsL2) are c_j / A_l with A_0 = pi,
//     A_1 = 2 pi / 3, A_2 = pi / 4 (the clamped-cosine convolution); a mirror
//     of one axis on import negates the coefficients odd in it
//     (x: 3, 4, 7; y: 1, 4, 5; z: 2, 5, 7).
#include <array>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "runtime/final_gather.h"
#include "runtime/probe_volume.h"

namespace bounce {

inline constexpr std::size_t kShCoefficients = 9;
inline constexpr std::size_t kProbeDirections = 14;

// The directions each probe gathers about: +x, -x, +y, -y, +z, -z, then the
// 8 unit cube diagonals (x, y, z each +-1/sqrt(3)), x changing fastest.
const std::array<glm::vec3, kProbeDirections>& probe_directions();

// The 9 real SH basis functions at unit direction n (the order above).
std::array<float, kShCoefficients> sh_basis(const glm::vec3& n);

// The irradiance E(n) = sum_j sh[j] Y_j(n) of one probe's 9 coefficients.
glm::vec3 sh_irradiance(const glm::vec3* sh, const glm::vec3& n);

// The least-squares fit of 9 SH coefficients to irradiance at the
// probe_directions(): row j holds the weights of the 14 irradiances in
// coefficient j, (Y^T Y)^-1 Y^T with Y the 14 x 9 basis matrix.
const std::array<std::array<float, kProbeDirections>, kShCoefficients>& sh_fit_matrix();

// Probes' SH from the irradiance at their directions: `direction_irradiance`
// holds kProbeDirections values per probe (probe p's direction k at
// p * kProbeDirections + k); `sh` gets kShCoefficients per probe (probe p's
// coefficient j at p * kShCoefficients + j).
void fit_probe_sh(const std::vector<glm::vec3>& direction_irradiance, std::vector<glm::vec3>& sh);

// A bake's light probes: where they are and the gather of their directions.
struct LightProbes {
  // The probes next to the surfaces first, then each volume's.
  std::vector<glm::vec3> position;
  // Rows for position.size() x kProbeDirections points: probe p's direction
  // k is point p * kProbeDirections + k. No near sources or spots: a probe
  // next to the surfaces stands half a voxel from them, and a volume's
  // probes are where its author wants them.
  FinalGather gather;
  // The probe volumes' lattices (runtime/probe_volume.h), in order.
  std::vector<ProbeLattice> volumes;
  std::size_t size() const { return position.size(); }
};

}  // namespace bounce
