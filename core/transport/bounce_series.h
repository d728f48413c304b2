#pragma once
// The K-bounce transport matrix T_K = M + M^2 + ... + M^K, M = diag(rho_c) F,
// by dense products only, and the choice of K for `--bounces auto`.
//
// Two schemes, the cheaper one is used (ties go to Horner: one buffer less):
//  * Horner, S_1 = M, S_(k+1) = M + M S_k: K - 1 products, 2 work buffers.
//  * Doubling along the binary digits of K, carrying P_k = M^k:
//      T_2k = T_k + P_k T_k,  P_2k = P_k P_k,  T_(k+1) = T_k + P_k M,
//    about 2 log2 K products (P is not formed when no later step reads it,
//    a final +1 being T_(k+1) = M + M T_k, and the first doubling needs only
//    M M), 3 work buffers. It wins from K = 4 on (K = 3 ties; K = 5: 3
//    products against 4; K = 8: 4 against 7; K = 64: 10 against 63).
// No cancellation anywhere: every term is non-negative, so float32 keeps a
// relative error of a few K n eps.
#include <cstddef>
#include <functional>
#include <vector>

#include "base/mapped_buffer.h"
#include "transport/gemm_backend.h"

namespace bounce {

enum class SeriesScheme { Horner, Doubling };

struct SeriesPlan {
  int bounces = 1;
  SeriesScheme scheme = SeriesScheme::Horner;
  int gemms = 0;  // of the chosen scheme
  int horner_gemms = 0;
  int doubling_gemms = 0;
};

SeriesPlan plan_series(int bounces);

// Sums the series as planned. `after_each_gemm` is called after every product
// (progress, cancellation). m is row-major n x n; the work buffers and the
// result are MatrixValues, mapped to files in an out-of-core bake.
MatrixValues sum_bounces(const MatrixValues& m, std::size_t n, const SeriesPlan& plan,
                         GemmBackend& gemm, const std::function<void()>& after_each_gemm = {});

// `--bounces auto`. The light of bounce h when every patch sends out one unit
// is e_h = 1^T M^h 1, the sum of the entries of M^h; it is found with
// matrix-vector products only (v_h = M v_(h-1)), so K is known before any
// matrix product and the cheap scheme can be used for it. K is the first
// count for which the next bounce adds less than `tolerance` of the light so
// far: e_(K+1) < tolerance * (e_1 + ... + e_K).
struct AutoBounces {
  int bounces = 1;
  bool converged = false;      // false: not reached by max_bounces
  double next_fraction = 0.0;  // e_(K+1) / (e_1 + ... + e_K)
  std::vector<double> energy;  // e_1, e_2, ... as computed
};

AutoBounces choose_auto_bounces(const float* m, std::size_t n, double tolerance, int max_bounces);

// What the bounces after K can add, relative to the first-hit light b:
// ||sum_(h>K) M^h b||_v <= c^(K+1) / (1 - c) ||b||_v for every b, with
// ||x||_v = max_i |x_i| / v_i the weighted max-norm in which ||M||_v = c, the
// Collatz-Wielandt upper bound of the spectral radius (spectral_radius.h).
// Infinite when c >= 1.
double truncation_bound(double norm_upper, int bounces);

}  // namespace bounce
