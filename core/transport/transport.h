#pragma once
// The multi-bounce transport matrix, one per colour channel c:
//   T_c = sum_(h=1..K) (diag(rho_c) F)^h,   K -> infinity: (I - diag(rho_c) F)^-1 - I.
// At run time the indirect light after the first hit is T_c b_c, with b_c the
// light leaving each patch after the first hit. F is the gathering form-factor
// matrix (F[p * n + q] = F_pq, energy leaving p that arrives at q), so
// M = diag(rho_c) F scales row p by the albedo of patch p.
//
// What the stage decides, and records as decisions (and left-outs/warnings in
// Diagnostics):
//  * channels: one matrix for a grey scene (every albedo has r = g = b within
//    1e-6), a matrix shared by two channels whose albedos agree, else three;
//  * K: explicit, infinity (Cholesky, else LU), or auto (bounce_series.h):
//    the series truncated where the next bounce adds less than the
//    tolerance, or the exact K = infinity when that is cheaper (it usually
//    is: one Cholesky solve costs about 1.2 products) or the series converges
//    too slowly; with the spectral radius of M (spectral_radius.h) and, for
//    finite K, a bound on what omitted bounces add;
//  * the series scheme (Horner or doubling, fewer products wins);
//  * the solve's method and precision (inverse_transport.h);
//  * the GEMM backend (gemm_selection.h), timed only when a series is
//    summed: K = infinity needs no product.
// Nothing non-finite leaves the stage: bad input and bad output both throw
// bounce::Error naming what is wrong.
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "base/diagnostics.h"
#include "base/progress.h"
#include "formfactor/form_factors.h"
#include "transport/inverse_transport.h"
#include "transport/transport_decision.h"
#include "transport/transport_executor.h"
#include "transport/transport_settings.h"

namespace bounce {

struct ChannelTransport {
  std::vector<int> rgb;  // the channels this matrix stands for: 0 = R, 1 = G, 2 = B
  // Row-major n x n: indirect light = T b. A std::vector whose storage is a
  // mapped file during an out-of-core bake (base/mapped_buffer.h).
  MatrixValues t;
  int bounces = 1;  // K, or TransportSettings::kInfiniteBounces
  // Auto: the K at which the series converged (also when the exact K =
  // infinity was computed because it was cheaper); 0 otherwise.
  int auto_bounces = 0;
  // "Horner", "doubling", "Cholesky float32", "Cholesky float64", "LU float32", "LU float64"
  std::string method;
  int gemms = 0;  // matrix products used
  // Floating-point operations of the products or of the factorisations and
  // solves (2 n^3 per product, n^3 / 3 per Cholesky, 2 n^3 per solve of n
  // right-hand sides, ...), for GFLOP/s.
  double flops = 0.0;
  // Spectral radius of M = diag(rho_c) F with its Collatz-Wielandt bounds: by
  // power iteration on M for finite K, read off the solved T for K = infinity
  // (spectral_radius_from_transport).
  double spectral_radius = 0.0;
  double spectral_radius_lower = 0.0;
  double spectral_radius_upper = 0.0;
  // Finite K: what the omitted bounces could add, relative to the first-hit
  // light, in the max-norm weighted by the Perron vector estimate:
  // c^(K+1) / (1 - c), c = spectral_radius_upper (bounce_series.h). 0 for
  // K = infinity; infinite when c >= 1.
  double truncation_bound = 0.0;
  // K = infinity: the condition number of the matrix factorised, kappa_1(S)
  // by LAPACKE_?pocon for Cholesky, kappa_inf(I - M) by LAPACKE_?gecon for LU
  // (inverse_transport.h). 0 for finite K.
  double condition_number = 0.0;
  TransportPrecision precision = TransportPrecision::Float32;
  double seconds = 0.0;
};

struct TransportResult {
  std::size_t n = 0;
  std::vector<ChannelTransport> channels;
  bool grey = false;
  std::string backend;  // GEMM backend used, or why none was needed
  // Backend::Auto's probe: size and best-of-3 seconds per backend (0 = not run).
  std::size_t probe_n = 0;
  double probe_openblas_seconds = 0.0;
  double probe_clblast_seconds = 0.0;
  double seconds = 0.0;
  double flops = 0.0;  // of every channel's products or solve
  std::vector<TransportDecision> decisions;

  // The matrix standing for channel rgb (0 = R, 1 = G, 2 = B).
  const ChannelTransport& channel(int rgb) const;
};

// `executor` (optional): runs the products and the solve elsewhere
// (transport_executor.h); settings.backend is then not used.
TransportResult compute_transport(const FormFactorMatrix& form_factors,
                                  const std::vector<glm::vec3>& albedo,
                                  const TransportSettings& settings, Progress* progress,
                                  Diagnostics& diagnostics, TransportExecutor* executor = nullptr);

}  // namespace bounce
