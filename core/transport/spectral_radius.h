#pragma once
// Spectral radius of a non-negative n x n matrix M (here diag(rho_c) F) by
// power iteration with sgemv. Perron-Frobenius: the spectral radius of a
// non-negative matrix is itself an eigenvalue with a non-negative eigenvector,
// so iterating on a positive vector converges to it (at the rate
// |lambda_2| / rho of the second eigenvalue).
//
// For any positive vector v the Collatz-Wielandt quotients bracket it:
//   min_i (M v)_i / v_i  <=  rho(M)  <=  max_i (M v)_i / v_i.
// The upper bound is also the norm of M induced by the weighted max-norm
// ||x||_v = max_i |x_i| / v_i, which is what makes the truncation bound of a
// K-bounce sum rigorous (see bounce_series.h).
#include <cstddef>
#include <vector>

namespace bounce {

struct SpectralRadius {
  double estimate = 0.0;  // ||M v||_2 / ||v||_2 at the last iteration
  double lower = 0.0;     // Collatz-Wielandt lower bound
  double upper = 0.0;     // Collatz-Wielandt upper bound = ||M||_v
  int iterations = 0;
  bool converged = false;      // upper - lower or the estimate settled to `tolerance`
  std::vector<float> weights;  // the positive v of the bounds (max entry 1)
};

// m: row-major n x n, non-negative. Stops when (upper - lower) <= tolerance *
// upper, or when the upper bound's remaining decrease, extrapolated from its
// geometric convergence, is below tolerance * upper (reducible matrices, e.g.
// with rows of zero albedo, keep the lower bound at 0), or after
// max_iterations.
SpectralRadius estimate_spectral_radius(const float* m, std::size_t n, int max_iterations = 100,
                                        double tolerance = 1e-4);

// The same bounds read off a solved T = (I - M)^-1 - I (t: row-major n x n),
// for K = infinity, where no power iteration on M is run. For any v > 0,
// u = (I - M)^-1 v = v + T v satisfies M u = u - v exactly, so the
// Collatz-Wielandt quotients of M at u are (T v)_i / (v + T v)_i, all below 1
// while v + T v > 0: a solution with a non-positive or non-finite entry there
// makes the upper bound infinite (the light does not settle). v is iterated
// as v <- T v, power iteration on T, whose eigenvalues lambda / (1 - lambda)
// converge faster than M's (ratio (lambda_2 / rho) (1 - rho) / (1 - lambda_2)
// against lambda_2 / rho). One sgemv on T per step.
SpectralRadius spectral_radius_from_transport(const float* t, std::size_t n,
                                              int max_iterations = 16, double tolerance = 1e-4);

}  // namespace bounce
