#pragma once
// The local matrix of dynamic radiosity: the multi-bounce matrix of a
// set of active patches, kept up to date as patches join or leave the set
// (a window of patches that follows the camera, an object added to the
// scene) by a rank-1 update instead of a new factorisation.
//
// Derivation. T = (I - M)^-1 - I with M = diag(rho) F over the active
// patches (transport/inverse_transport.h; K = infinity). Adding patch k with
// u = M[:, k] (rho_i F_ik: light k sends to each active patch i) and
// v = M[k, :] (rho_k F_kj) gives the bordered system
//   I - M' = [[I - M, -u], [-v, 1]],
// whose inverse by the Schur complement S = I - M - u v is, with
// G = T + I = (I - M)^-1, a = G u, b = v G and sigma = v G u:
//   S^-1            = G + a b / (1 - sigma)      (Sherman-Morrison)
//   (I - M')^-1 col k = a / (1 - sigma),  row k = b / (1 - sigma),
//   (I - M')^-1 [k, k] = 1 / (1 - sigma).
// So T' = T + a b / (1 - sigma) on the old patches, T'[:, k] = a / (1 - sigma),
// T'[k, :] = b / (1 - sigma), T'[k, k] = sigma / (1 - sigma). In the paper's
// names a = g''_c + f_c and b = g''_r + f_r (with the albedos folded into
// u and v); sigma is the share of light that leaves k and comes back to k
// after any number of bounces, and 1 / (1 - sigma) sums those returns, which
// the paper's product (g''_c + f_c)(g''_r + f_r) truncates. Removing patch k
// is the inverse step: the inverse of a principal block is
// G_oo - G_ok G_ko / G_kk, i.e.
//   T_removed = T - T[:, k] T[k, :] / (1 + T[k, k])   on the remaining patches.
// Both cost two matrix-vector products and one outer product, O(N^2), against
// O(N^3) for a new LU; the work vectors are four N-vectors (u, v, a, b).
//
// What is exact and what is not: for K = infinity the update is exact up to
// rounding. It keeps every form factor between the old patches as it was, so
// it cannot express occlusion: a patch added between two others does not
// shadow them (an added object's blocking needs its own correction or a new
// bake); and for a truncated-series T (finite K) the added paths through k
// are of every length, not at most K.
//
// Precision: float32, the precision of the bake's T and of the run-time
// product (the window lives next to it on the device and a float64 copy
// would double its memory and bandwidth); sigma and 1 - sigma are computed in
// float64, where the cancellation when sigma -> 1 would otherwise happen.
// Rounding per update is about N * FLT_EPSILON relative to (|T| + 1)^2 |u| |v|
// (the two sgemv's), far below the bake's own compression error.
#include <cstddef>
#include <vector>

namespace bounce {

class LocalTransport {
 public:
  // t: row-major n x n multi-bounce matrix (K = infinity) of one colour
  // channel over the patches marked active; rows and columns of inactive
  // patches must be zero (they are checked). Throws bounce::Error on sizes.
  LocalTransport(std::vector<float> t, std::size_t n, std::vector<bool> active);

  // Adds inactive patch k. `column[i]` = M[i][k] = rho_i F_ik, `row[j]` =
  // M[k][j] = rho_k F_kj, n entries each (entries of inactive patches and of k
  // itself are ignored). Returns sigma, the return share of k. Throws
  // bounce::Error when k is active or out of range, or sigma >= 1 (the
  // enlarged system has no bounded solution).
  double add_patch(std::size_t k, const std::vector<float>& column, const std::vector<float>& row);

  // Removes active patch k: its row and column become zero.
  void remove_patch(std::size_t k);

  const std::vector<float>& matrix() const { return t_; }
  std::size_t size() const { return n_; }
  bool active(std::size_t k) const { return active_.at(k); }

 private:
  void check_index(std::size_t k, const char* what) const;
  std::size_t n_;
  std::vector<float> t_;
  std::vector<bool> active_;
  std::vector<float> u_, v_, a_, b_;  // the four work vectors
};

// Column k and row k of M = diag(rho) F for one channel: column[i] = rho[i] *
// F[i * n + k], row[j] = rho[k] * F[k * n + j] (F gathering, row-major).
void transport_column_and_row(const float* f, const std::vector<float>& rho, std::size_t k,
                              std::vector<float>& column, std::vector<float>& row);

}  // namespace bounce
