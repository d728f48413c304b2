#pragma once
// The Cholesky path of solve_infinite_bounces_in_place (inverse_transport.h
// explains the similarity I - M^T = E^-1 S E it rests on).
//
// Patches of albedo 0 (set Z; the others are P): row z of M is zero, so
//   I - M^T = [[I - M_PP^T, 0], [-M_PZ^T, I]]   (rows and columns P, then Z)
// is block lower triangular. The rows P of T^T solve the symmetrisable system
// of P alone, and the rows Z follow by one product:
//   X_P = E^-1 S^-1 E M^T_P,   X_Z = M^T_Z + M_PZ^T X_P.
// Each right-hand side column is gathered into that order, solved and
// scattered back, one solve block at a time.
#include <cstddef>
#include <optional>
#include <string>

#include "transport/inverse_transport.h"

namespace bounce {

struct CholeskyAttempt {
  std::optional<InverseTransport> result;  // set when m holds T
  std::string why_not;                     // else why the LU must be used; m is untouched
  double flops = 0.0;                      // spent either way
};

// m: row-major n x n M = diag(rho) F; options.area and options.albedo hold
// n values each.
CholeskyAttempt solve_by_cholesky(float* m, std::size_t n, double spectral_radius,
                                  const InverseOptions& options);

// float64 results with fewer than two correct digits are refused, not
// shipped: throws bounce::Error when condition * DBL_EPSILON > 1e-2.
void check_float64_condition(double condition);

}  // namespace bounce
