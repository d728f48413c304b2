#pragma once
// K -> infinity: T = (I - M)^-1 - I = (I - M)^-1 M, so T solves (I - M) T = M
// -- one factorisation and n right-hand sides, no explicit inverse and no
// subtraction of I (which would cancel digits on the diagonal).
//
// Row-major buffers are handed to LAPACK as column-major, i.e. transposed:
// the system solved is (I - M^T) T^T = M^T, the transpose of T (I - M) = M,
// which holds because M commutes with (I - M)^-1. No copy or transposition is
// needed, and each block of right-hand sides is a contiguous block of rows of T.
//
// Cholesky (the default when patch areas are given). Balanced form factors
// are reciprocal, A_p F_pq = A_q F_qp (docs/method.md 5a), so with
// E = diag(sqrt(rho / A)) over the patches of albedo rho > 0 the matrix
// B = E (A F) E = E M^T E^-1 is symmetric, and I - M^T = E^-1 (I - B) E is
// similar to the symmetric S = I - B, whose eigenvalues are 1 - lambda(M):
// S is positive definite exactly when the spectral radius of M is below 1,
// so a Cholesky factorisation that succeeds proves the light settles. The
// solve is then T^T = E^-1 S^-1 (E M^T) with ?potrf + ?potrs, 7/3 n^3 flops
// against the LU's 8/3 n^3. Patches of albedo 0 have a zero row in M and in
// T; their columns of T^T (rows of M^T) follow from the others by one product
// (symmetric_transport.h). F is reciprocal to float rounding only, so B is
// symmetrised; an asymmetry beyond rounding (F not balanced, e.g.
// --closure-rays 0), no areas, or a factorisation that breaks down in float64
// (not positive definite) fall back to the LU with the reason recorded.
//
// Precision rule. The forward error is about kappa * eps, with kappa the
// condition number of the matrix factorised (S for Cholesky, I - M for LU).
// float32 is used when kappa * FLT_EPSILON <= InverseOptions::float32_error_limit (1e-5),
// float64 otherwise. When the spectral radius rho(M) is known, kappa is first
// bounded from below without factorising: kappa_1(S) >= ||S||_1 / (1 - rho) and
// kappa_inf(I - M) >= ||I - M||_inf / (1 - rho) (every norm bounds the spectral
// radius of the inverse, which is 1 / (1 - rho) for non-negative M), and that
// alone sends stiff systems (albedo near 1 in a closed scene) straight to
// float64; otherwise float32 is factorised, its ?pocon / ?gecon estimate
// checked, and the factorisation redone in float64 when it fails the rule.
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "base/mapped_buffer.h"

namespace bounce {

enum class TransportPrecision { Float32, Float64 };

const char* precision_name(TransportPrecision p);

enum class InverseMethod { Cholesky, LU };

const char* method_name(InverseMethod m);

struct InverseTransport {
  std::vector<float> t;  // row-major n x n
  InverseMethod method = InverseMethod::LU;
  TransportPrecision precision = TransportPrecision::Float32;
  // The condition number of the matrix factorised, estimated on its
  // factorisation: kappa_1(S) by LAPACKE_?pocon (Cholesky), kappa_inf(I - M) =
  // kappa_1(I - M^T) by LAPACKE_?gecon (LU).
  double condition = 0.0;
  double condition_lower_bound = 0.0;  // norm / (1 - rho) before factorising; 0: rho not given
  bool refactorised = false;           // float32 failed the rule after factorising
  std::string why;                     // the precision rule as applied, for the manifest
  // Why the LU was used although patch areas were given (empty otherwise).
  std::string lu_reason;
  // Largest |B_pq - B_qp| / max(|B_pq|, |B_qp|) before symmetrising (Cholesky
  // only): the departure of A F from symmetry, float rounding when balanced.
  double asymmetry = 0.0;
  // Floating-point operations of the factorisations, solves and products run
  // (a broken-down or refactorised attempt included), for GFLOP/s.
  double flops = 0.0;
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
  // Patch areas and this channel's albedo (n each): with them the solve uses
  // Cholesky when A F is symmetric to float rounding; without them, LU.
  std::span<const float> area;
  std::span<const float> albedo;
  // Largest relative asymmetry of A F accepted for Cholesky: float32 rounding
  // of the balanced F and of rho F leaves a few 1e-7 per entry.
  double asymmetry_limit = 1e-6;
};

// ||I - M||_inf / (1 - rho): a lower bound of kappa_inf(I - M) known before
// factorising (infinite for rho >= 1, 0 when rho < 0, i.e. not known). m is row-major n x n.
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
// this machine (2 cores, the 4348-patch Cornell box): LU float32 1.3-1.4,
// float64 3.0-3.5; Cholesky float32 1.2 (7/3 n^3 flops against the product's
// 2 n^3), float64 about twice that. Used by --bounces auto to choose between
// a truncated series and the exact K = infinity.
double solve_cost_in_gemms(InverseMethod method, TransportPrecision precision);

// m: row-major n x n M = diag(rho_c) F, taken by value so its memory is reused
// (float32) or released (float64) as soon as possible. `spectral_radius` is
// the estimate of rho(M), < 1, or negative when not known (the precision rule
// then rests on the estimate after factorising). Throws bounce::Error when
// I - M is singular.
InverseTransport solve_infinite_bounces(std::vector<float> m, std::size_t n, double spectral_radius,
                                        const InverseOptions& options = {});

// The same in place: m (row-major n x n M) is overwritten with T and the
// result's t is left empty. The factorisation is a MatrixBuffer (a mapped
// file in an out-of-core bake), and float64 converts the right-hand side one
// solve block at a time, so the solve holds m and the factorisation only:
// 2 n^2 floats in float32, 3 n^2 in float64 (Cholesky with patches of albedo
// 0: plus their n_0 (n - n_0) values of M, within the same bound as the
// factorisation shrinks to (n - n_0)^2). Same arithmetic, bit for bit, as
// the vector version.
InverseTransport solve_infinite_bounces_in_place(float* m, std::size_t n, double spectral_radius,
                                                 const InverseOptions& options = {});

}  // namespace bounce
