#pragma once
// What compression costs in accuracy, measured against the exact transport
// matrix: the matrix figures of the published method (mean, max, sum of |error|) plus
// the relative Frobenius error, and the error of the indirect light itself,
// the thing a user sees, for a fixed set of first-hit light vectors.
//
// Indirect light of one light: I_k = T_(c(k)) b_k for each colour channel k,
// with b the light leaving each patch after the first hit. Its error is the
// area-weighted relative RMS over patches and channels,
//   sqrt(sum_p A_p sum_k (I~_pk - I_pk)^2) / sqrt(sum_p A_p sum_k I_pk^2),
// reported as mean and max over the lights.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "compress/codec.h"
#include "compress/matrix_error.h"

namespace bounce {

struct IndirectLightError {
  std::size_t lights = 0;  // lights with any first-hit light on the patches
  double rel_rms_mean = 0.0;
  double rel_rms_max = 0.0;
  // Per light of the probe, in its order: the relative RMS error, 0 for a
  // light with no indirect light.
  std::vector<double> per_light;
  double rel_rms_sum = 0.0;  // over the lights counted, for the mean

  // Counts the next light of the probe from its squared error and squared
  // reference (each summed with its weights): its relative RMS
  // sqrt(err2 / ref2), or 0 and not counted when ref2 is 0.
  void add_light(double err2, double ref2);
};

struct CompressionErrors {
  MatrixError matrix;                 // every stored channel together
  std::vector<MatrixError> channels;  // per stored channel
  IndirectLightError indirect;
};

struct IndirectLightProbe {
  // Per light, b per patch (R, G, B).
  std::vector<std::vector<glm::vec3>> first_hit;
  // Stored matrix used for colour channel k (0 = R, 1 = G, 2 = B).
  std::array<int, 3> channel_of_rgb{0, 1, 2};
  // Patch areas, the weights of the RMS.
  std::vector<float> area;
};

// `exact[c]`: stored channel c of the exact matrix (n x n, row-major, patch
// order). A sampled compression is measured on its rows only. With `abs_error_sum`, also returns
// the sum over stored channels of |T~ - T| per entry (n x n, patch order) for error pictures.
CompressionErrors measure_compression(const std::vector<const float*>& exact,
                                      const CompressedMatrix& compressed,
                                      const IndirectLightProbe& probe,
                                      std::vector<float>* abs_error_sum = nullptr,
                                      Progress* progress = nullptr);

// The same indirect-light figure for any approximate matrices (one per stored
// channel), e.g. the dense ones of another bake.
IndirectLightError indirect_light_error(const std::vector<const float*>& exact,
                                        const std::vector<const float*>& approx, std::size_t n,
                                        const IndirectLightProbe& probe);
// The same on the patches `rows` only (ascending; empty: every patch), with
// `approx` holding just those rows (rows.size() x n each): the figure of a
// sample of rows, as the error budget's search measures it.
IndirectLightError indirect_light_error_on_rows(const std::vector<const float*>& exact,
                                                const std::vector<const float*>& approx,
                                                std::size_t n, std::span<const std::uint32_t> rows,
                                                const IndirectLightProbe& probe);

}  // namespace bounce
