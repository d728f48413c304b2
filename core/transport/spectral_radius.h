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

}  // namespace bounce
