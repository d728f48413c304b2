#pragma once
// What an approximate transport matrix (the compressed one, decoded) changes
// in one light's indirect light on the patches: T b against T~ b, each
// patch's relative error (vertex_relative_errors: the largest channel's
// |x - y| / max(|y|, 5% of the mean |y|)), the area-weighted relative RMS
// over patches and R, G, B (the bake's indirect-light error figure). Which
// entries of the compressed matrix make one patch's difference:
// compress/row_error_contributions.h.
#include <array>
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

// sqrt(sum_p A_p |x_p - y_p|^2 / sum_p A_p |y_p|^2); 0 when y is zero.
// Throws bounce::Error when the sizes differ.
double area_weighted_relative_rms(const std::vector<float>& area,
                                  const std::vector<glm::vec3>& test,
                                  const std::vector<glm::vec3>& exact);

struct PatchLightError {
  std::vector<glm::vec3> exact, approx;  // T b and T~ b per patch
  std::vector<float> relative;           // per patch
  double rel_rms = 0.0;                  // area-weighted
};

// `exact`, `approx`: the stored channels (n x n, row-major, patch order);
// `channel_of_rgb[k]`: the stored channel colour k uses; `b`: the light
// leaving each patch after the first hit.
PatchLightError patch_light_error(const std::vector<const float*>& exact,
                                  const std::vector<const float*>& approx, std::size_t n,
                                  const std::array<int, 3>& channel_of_rgb,
                                  const std::vector<glm::vec3>& b, const std::vector<float>& area);

}  // namespace bounce
