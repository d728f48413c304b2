// The local matrix (dynamic/local_transport.h): adding and removing a patch
// by the rank-1 update must equal recomputing T = (I - M)^-1 - I from
// scratch with the LU of transport/inverse_transport.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <vector>

#include "base/error.h"
#include "base/random.h"
#include "dynamic/local_transport.h"
#include "transport/inverse_transport.h"

namespace bounce {
namespace {

// A random closed-ish scene: F >= 0 with row sums `row_sum` (< 1, as form
// factors of a patch sum to at most 1), albedos in [rho_min, 0.95].
struct SmallScene {
  std::size_t n;
  std::vector<float> f, rho;
};

SmallScene random_scene(std::size_t n, float row_sum, std::uint64_t seed, float rho_min = 0.3f) {
  SmallScene s{n, std::vector<float>(n * n, 0.0f), std::vector<float>(n)};
  Rng rng(seed, 0);
  for (std::size_t i = 0; i < n; ++i) {
    s.rho[i] = rho_min + (0.95f - rho_min) * rng.uniform();
    double sum = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      // Sparse-ish and uneven, like real form factors; no self-transfer.
      const float x = rng.uniform();
      s.f[i * n + j] = (i == j || x < 0.3f) ? 0.0f : x * x;
      sum += s.f[i * n + j];
    }
    for (std::size_t j = 0; j < n; ++j)
      s.f[i * n + j] = static_cast<float>(s.f[i * n + j] * row_sum / sum);
  }
  return s;
}

// T from scratch over the active patches (rows and columns of inactive ones
// of M zeroed, which zeroes theirs in T), in float64.
InverseTransport recompute(const SmallScene& s, const std::vector<bool>& active) {
  std::vector<float> m(s.n * s.n, 0.0f);
  for (std::size_t i = 0; i < s.n; ++i)
    for (std::size_t j = 0; j < s.n; ++j)
      if (active[i] && active[j]) m[i * s.n + j] = s.rho[i] * s.f[i * s.n + j];
  InverseOptions options;
  options.force = TransportPrecision::Float64;
  // rho(M) <= max rho * max row sum of F bounds the spectral radius.
  return solve_infinite_bounces(std::move(m), s.n, 0.95 * 0.99, options);
}

double max_abs(const std::vector<float>& a) {
  double m = 0.0;
  for (float x : a) m = std::max(m, std::abs(static_cast<double>(x)));
  return m;
}

double max_diff(const std::vector<float>& a, const std::vector<float>& b) {
  double m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    m = std::max(m, std::abs(static_cast<double>(a[i]) - b[i]));
  return m;
}

// Tolerance relative to max |T|. Each update does two float32 sgemv's of
// length n (forward error <= n eps |T| |u|, gamma_n bound) and scales by
// 1 / (1 - sigma) <= kappa; the float32 input T carries eps |T| that the
// update multiplies by at most ||T + I|| <= kappa again. So per update
// (n + kappa) kappa eps, summed over the updates of the sequence.
double tolerance(std::size_t n, double kappa, int updates) {
  return updates * (static_cast<double>(n) + kappa) * kappa * FLT_EPSILON;
}

TEST(DynamicLocalMatrix, AddAndRemoveMatchRecomputation) {
  const SmallScene s = random_scene(48, 0.95f, 7);
  std::vector<bool> all(s.n, true);
  const InverseTransport full = recompute(s, all);
  const double scale = max_abs(full.t);
  std::vector<float> column, row;

  for (std::size_t k : {std::size_t{0}, std::size_t{17}, std::size_t{47}}) {
    // Remove k from the full matrix.
    LocalTransport local(full.t, s.n, all);
    local.remove_patch(k);
    std::vector<bool> without = all;
    without[k] = false;
    const InverseTransport reduced = recompute(s, without);
    const double kappa = std::max(full.condition, reduced.condition);
    EXPECT_LE(max_diff(local.matrix(), reduced.t) / scale, tolerance(s.n, kappa, 1))
        << "remove " << k;

    // Add it back to the recomputed reduced matrix.
    LocalTransport grow(reduced.t, s.n, without);
    transport_column_and_row(s.f.data(), s.rho, k, column, row);
    const double sigma = grow.add_patch(k, column, row);
    EXPECT_GT(sigma, 0.0);
    EXPECT_LT(sigma, 1.0);
    EXPECT_LE(max_diff(grow.matrix(), full.t) / scale, tolerance(s.n, kappa, 1)) << "add " << k;
  }
}

TEST(DynamicLocalMatrix, WindowOfPatchesThroughManyUpdates) {
  // A window that starts with half the patches and moves: add 8, remove 8,
  // compared with recomputation at the end. Few patches, bright and strongly
  // coupled, so the return share sigma is large (~0.1): dropping the
  // 1 / (1 - sigma) factor would miss the tolerance by orders of magnitude.
  const SmallScene s = random_scene(16, 0.98f, 11, 0.8f);
  std::vector<bool> active(s.n, false);
  for (std::size_t i = 0; i < s.n / 2; ++i) active[i] = true;
  LocalTransport local(recompute(s, active).t, s.n, active);
  std::vector<float> column, row;
  double largest_sigma = 0.0;
  for (std::size_t step = 0; step < 8; ++step) {
    const std::size_t add = s.n / 2 + step, remove = step;
    transport_column_and_row(s.f.data(), s.rho, add, column, row);
    largest_sigma = std::max(largest_sigma, local.add_patch(add, column, row));
    local.remove_patch(remove);
    active[add] = true;
    active[remove] = false;
  }
  const InverseTransport ref = recompute(s, active);
  EXPECT_GT(largest_sigma, 0.05);
  EXPECT_LE(max_diff(local.matrix(), ref.t) / max_abs(ref.t), tolerance(s.n, ref.condition, 16));
  for (std::size_t i = 0; i < s.n; ++i) EXPECT_EQ(local.active(i), active[i]);
}

TEST(DynamicLocalMatrix, RejectsBadUpdates) {
  const SmallScene s = random_scene(8, 0.9f, 3);
  std::vector<bool> active(s.n, true);
  active[7] = false;
  LocalTransport local(recompute(s, active).t, s.n, active);
  std::vector<float> column, row;
  transport_column_and_row(s.f.data(), s.rho, 7, column, row);
  EXPECT_THROW(local.add_patch(3, column, row), Error);  // already active
  EXPECT_THROW(local.remove_patch(7), Error);            // not active
  EXPECT_THROW(local.add_patch(9, column, row), Error);  // out of range
  // A patch that sends all its light to a patch that sends it all back: sigma >= 1.
  std::vector<float> loop_column(s.n, 0.0f), loop_row(s.n, 0.0f);
  loop_column[0] = 1.0f;
  loop_row[0] = 1.0f;
  LocalTransport empty(std::vector<float>(s.n * s.n, 0.0f), s.n, std::vector<bool>(s.n, false));
  std::vector<float> none(s.n, 0.0f);
  empty.add_patch(0, none, none);
  EXPECT_THROW(empty.add_patch(1, loop_column, loop_row), Error);
  // Non-zero entries of an inactive patch.
  std::vector<float> t(4, 1.0f);
  EXPECT_THROW(LocalTransport(t, 2, {true, false}), Error);
}

}  // namespace
}  // namespace bounce
