#pragma once
// Balanced form factors: F scaled so that every row sums to its patch's
// closure (closure.h) and reciprocity A_P F_PQ = A_Q F_QP holds to float
// rounding.
//
// The quadrature of F (form_factors.h) leaves rows a little off their closure
// (the near field over-counts by up to ~1%, visibility from a few rays under-
// or over-counts) and the two directions of a near pair a little apart. Both
// are energy errors the multi-bounce solve amplifies by up to 1 / (1 - rho s)^2,
// so a closed room at albedo 0.99 came out 32% too bright.
//
// Method: the exchange matrix G = diag(A) F is first made symmetric,
// S = (G + G^T) / 2, then scaled symmetrically, G' = diag(x) S diag(x), with
// x > 0 chosen so that the rows of G' are the targets t_P = A_P c_P. A
// symmetric scaling keeps G' symmetric, which is reciprocity for
// F' = diag(A)^-1 G'. x solves x_P (S x)_P = t_P, found by the symmetric
// Sinkhorn-Knopp iteration x_P <- sqrt(x_P t_P / (S x)_P) (the square root
// damps the oscillation of the plain update), in float64, until every row is
// within `tolerance` of its target (relative), or `max_iterations`, or the
// residual stagnates; then rows still above their target are scaled down
// symmetrically, so that no row ever exceeds its closure. S is held
// in place of F (float32, symmetric), so the stage needs no memory beyond F.
// Each row's sum runs in a fixed order on one thread: the result does not
// depend on the thread count (the distributed bake balances on the root, bit
// for bit as one process does).
#include <cstddef>
#include <vector>

#include "base/progress.h"
#include "formfactor/form_factors.h"

namespace bounce {

struct BalanceSettings {
  double tolerance = 1e-7;  // float32 rounding of F's entries is ~6e-8
  int max_iterations = 2000;
  // A row is scaled up by at most this factor to meet its closure.
  double max_row_scale = 4.0;
  // Stop when the residual has not fallen by 1% in this many iterations.
  int stagnation_iterations = 50;
};

struct BalanceStats {
  int iterations = 0;
  bool converged = false;
  double residual = 0.0;  // max_P |row_P - c_P| / c_P after balancing (float64 rows)
  // Row scale per patch: balanced row sum / raw row sum (1 where the raw row
  // was already at its closure).
  std::vector<float> row_scale;
  double row_scale_min = 1.0;
  double row_scale_max = 1.0;
  // Patches whose closure ray found no surface while their raw row is not
  // empty: their raw row sum is kept as the target (the rays missed what the
  // quadrature saw; zeroing the row would cut the patch off).
  std::size_t kept_raw_targets = 0;
  std::vector<std::size_t> raw_target_patches;  // which ones
  // Patches whose closure lay beyond max_row_scale of their raw row: their
  // target is the nearest bound instead.
  std::size_t limited_targets = 0;
};

// Scales `f` in place and records `area` in it (f.area). `area` and
// `closure` are per patch (closure in [0, 1]).
BalanceStats balance_form_factors(FormFactorMatrix& f, const std::vector<float>& area,
                                  const std::vector<float>& closure,
                                  const BalanceSettings& settings = {},
                                  Progress* progress = nullptr);

}  // namespace bounce
