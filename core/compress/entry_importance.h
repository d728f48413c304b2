#pragma once
// How much an error in each entry of the transport matrix shows in the
// indirect light, for choosing which entries to keep exactly and where the
// block encoder spends its precision.
//
// The indirect light of a light is I = T b. An error E in T adds E b, and
// its area-weighted square over patches, for independent entry errors, is
//   sum_i A_i (sum_j E_ij b_j)^2  ~  sum_ij E_ij^2 A_i b_j^2.
// Relative to the light's own sum_i A_i I_i^2, and averaged over the
// evaluation lights, an error in entry (i, j) costs E_ij^2 row(i) column(j)
// with row(i) = A_i and column(j) = mean over lights of b_j^2 / |I|^2. A
// column no evaluation light reaches would weigh nothing; a floor keeps every
// column in play for the lights the evaluation set does not contain.
#include <array>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

struct EntryImportance {
  // Squared-error weights, each scaled to mean 1.
  std::vector<float> row;                  // n, shared by every stored channel
  std::vector<std::vector<float>> column;  // per stored channel, n

  // The weight of a squared error in entry (i, j) of stored channel c.
  float weight(std::size_t c, std::size_t i, std::size_t j) const { return row[i] * column[c][j]; }
};

// Floor of a column's weight, as a share of the mean column weight.
inline constexpr float kColumnWeightFloor = 0.1f;

// `exact[c]`: stored channel c (n x n, row-major); `first_hit`: per light, b
// per patch (R, G, B); `channel_of_rgb[k]`: the stored channel colour k uses;
// `area`: per patch. Lights whose exact indirect light is zero add nothing.
// `light_factor` (empty, or one per light): how much more each light counts
// than the others.
EntryImportance light_importance(const std::vector<const float*>& exact, std::size_t n,
                                 const std::vector<std::vector<glm::vec3>>& first_hit,
                                 const std::array<int, 3>& channel_of_rgb,
                                 const std::vector<float>& area,
                                 const std::vector<double>& light_factor = {});

}  // namespace bounce
