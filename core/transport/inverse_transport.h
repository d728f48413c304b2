#pragma once
// K -> infinity: T = (I - M)^-1 - I = (I - M)^-1 M, so T solves (I - M) T = M
// -- one LU factorisation and n right-hand sides, no explicit inverse and no
// subtraction of I (which would cancel digits on the diagonal).
//
// Row-major buffers are handed to LAPACK as column-major, i.e. transposed:
// the factorised matrix is I - M^T and the system solved is
// (I - M^T) T^T = M^T, the transpose of T (I - M) = M, which holds because
// M commutes with (I - M)^-1. No copy or transposition is needed, and each
// block of right-hand sides is a contiguous block of rows of T.
//
// Precision rule. The forward error of an LU solve is about kappa * eps, with
// kappa the condition number. float32 is used when kappa * FLT_EPSILON <=
// InverseOptions::float32_error_limit (1e-5), float64 otherwise. kappa is first bounded from below
// without factorising, kappa_inf(I - M) >= ||I - M||_inf / (1 - rho(M))
// (every norm bounds the spectral radius of (I - M)^-1, which is
// 1 / (1 - rho) for non-negative M), and that alone sends stiff systems
// (albedo near 1 in a closed scene) straight to float64; otherwise float32 is
// factorised, its ?gecon estimate checked, and the factorisation redone in
// float64 when it fails the rule.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "base/mapped_buffer.h"

namespace bounce {

enum class TransportPrecision { Float32, Float64 };

const char* precision_name(TransportPrecision p);

struct InverseTransport {
  std::vector<float> t;  // row-major n x n
  TransportPrecision precision = TransportPrecision::Float32;
  // kappa_inf(I - M) = kappa_1(I - M^T) estimated by LAPACKE_?gecon on the
  // factorisation that was used.
  double condition = 0.0;
  double condition_lower_bound = 0.0;  // ||I - M||_inf / (1 - rho), before factorising
  bool refactorised = false;           // float32 failed the rule after factorising
  std::string why;                     // the precision rule as applied, for the manifest
};

struct InverseOptions {
  // Largest kappa * FLT_EPSILON accepted for float32. 1e-5 relative: the
  // tolerance the tests hold the two GEMM backends to, two orders above
  // float32 storage, far below the compression error; float64 costs about
  // twice the time, which a stiff scene is worth.
  double float32_error_limit = 1e-5;
  std::optional<TransportPrecision> force;  // the bench times both
  int solve_blocks = 12;                    // right-hand-side blocks, one tick each
  // Called once after the factorisation and once per solve block.
  std::function<void()> tick;
};

// ||I - M||_inf / (1 - rho): a lower bound of kappa_inf(I - M) known before
// factorising (infinite for rho >= 1). m is row-major n x n.
double condition_lower_bound(const float* m, std::size_t n, double spectral_radius);

// The precision the rule picks from the lower bound alone (the factorisation
// can still move float32 to float64), and the rule as applied for the
// manifest (empty when float32 passes it).
struct PrecisionChoice {
  TransportPrecision precision = TransportPrecision::Float32;
  std::string why;
};
PrecisionChoice precision_before_factorising(double condition_lower_bound,
                                             const InverseOptions& options = {});
TransportPrecision predicted_precision(double condition_lower_bound,
                                       const InverseOptions& options = {});

// The cost of the whole solve in n x n OpenBLAS sgemm products, measured on
// this machine (2 cores, N = 2048 and the 4328-patch Cornell box, one run,
// back to back): float32 1.3-1.4, float64 3.0-3.5. Used by --bounces auto to
// choose between a truncated series and the exact K = infinity.
double lu_cost_in_gemms(TransportPrecision precision);

// m: row-major n x n M = diag(rho_c) F, taken by value so its memory is reused
// (float32) or released (float64) as soon as possible. `spectral_radius` is
// the estimate of rho(M), < 1. Throws bounce::Error when I - M is singular.
InverseTransport solve_infinite_bounces(std::vector<float> m, std::size_t n, double spectral_radius,
                                        const InverseOptions& options = {});

// The same in place: m (row-major n x n M) is overwritten with T and the
// result's t is left empty. The factorisation is a MatrixBuffer (a mapped
// file in an out-of-core bake), and float64 converts the right-hand side one
// solve block at a time, so the solve holds m and the factorisation only:
// 2 n^2 floats in float32, 3 n^2 in float64. Same arithmetic, bit for bit,
// as the vector version.
InverseTransport solve_infinite_bounces_in_place(float* m, std::size_t n, double spectral_radius,
                                                 const InverseOptions& options = {});

}  // namespace bounce
