#include "transport/spectral_radius.h"

#include <cblas.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "transport/blas_int.h"

namespace bounce {

namespace {

// A floor on the iterate keeps it strictly positive (the bounds need v > 0)
// without moving the estimate: 1e-6 of the largest entry is far below what a
// few dozen iterations resolve.
constexpr float kFloor = 1e-6f;

// Whether a geometrically converging sequence has settled: its remaining
// change, extrapolated as change_k q / (1 - q) with q = change_k / change_(k-1),
// is below tolerance * value (or it stopped changing).
struct Settling {
  double previous = -1.0;
  double previous_change = -1.0;
  bool settled(double value, double tolerance) {
    bool done = false;
    if (previous >= 0.0) {
      const double change = std::abs(value - previous);
      if (change <= tolerance * 1e-3 * value) {
        done = true;
      } else if (previous_change > 0.0) {
        const double q = change / previous_change;
        done = q < 1.0 && change * q / (1.0 - q) <= tolerance * value;
      }
      previous_change = change;
    }
    previous = value;
    return done;
  }
};

}  // namespace

SpectralRadius estimate_spectral_radius(const float* m, std::size_t n, int max_iterations,
                                        double tolerance) {
  SpectralRadius r;
  if (n == 0) return r;
  const int k = blas_dim(n, "cblas_sgemv");
  std::vector<float> v(n, 1.0f), w(n);
  Settling upper_track, estimate_track;
  for (int it = 1; it <= std::max(max_iterations, 1); ++it) {
    cblas_sgemv(CblasRowMajor, CblasNoTrans, k, k, 1.0f, m, k, v.data(), 1, 0.0f, w.data(), 1);
    double vv = 0.0, ww = 0.0, lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    float w_max = 0.0f;
    for (std::size_t i = 0; i < n; ++i) {
      const double q = static_cast<double>(w[i]) / static_cast<double>(v[i]);
      lo = std::min(lo, q);
      hi = std::max(hi, q);
      vv += static_cast<double>(v[i]) * v[i];
      ww += static_cast<double>(w[i]) * w[i];
      w_max = std::max(w_max, w[i]);
    }
    r.iterations = it;
    r.estimate = std::sqrt(ww / vv);
    r.lower = lo;
    r.upper = hi;
    r.weights = v;
    if (w_max <= 0.0f || !std::isfinite(w_max)) {
      r.converged = w_max <= 0.0f;  // M v = 0 for v > 0: M = 0, rho = 0 exactly
      break;
    }
    if (hi - lo <= tolerance * hi) {
      r.converged = true;
      break;
    }
    // Reducible matrices (rows of zero albedo, parts that do not see each
    // other) hold the lower bound below rho for good. Then stop when both the
    // upper bound and the estimate have settled.
    const bool upper_settled = upper_track.settled(hi, tolerance);
    const bool estimate_settled = estimate_track.settled(r.estimate, tolerance);
    if (upper_settled && estimate_settled) {
      r.converged = true;
      break;
    }
    for (std::size_t i = 0; i < n; ++i) v[i] = w[i] / w_max + kFloor;
  }
  return r;
}

SpectralRadius spectral_radius_from_transport(const float* t, std::size_t n, int max_iterations,
                                              double tolerance) {
  SpectralRadius r;
  if (n == 0) return r;
  const int k = blas_dim(n, "cblas_sgemv");
  std::vector<float> v(n, 1.0f), w(n);
  double previous_upper = -1.0;
  for (int it = 1; it <= std::max(max_iterations, 1); ++it) {
    cblas_sgemv(CblasRowMajor, CblasNoTrans, k, k, 1.0f, t, k, v.data(), 1, 0.0f, w.data(), 1);
    double uu = 0.0, mm = 0.0, lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double u = static_cast<double>(v[i]) + static_cast<double>(w[i]);  // (I - M)^-1 v
      if (!(u > 0.0) || !std::isfinite(u)) {
        r.iterations = it;
        r.estimate = r.upper = std::numeric_limits<double>::infinity();
        return r;
      }
      const double q = static_cast<double>(w[i]) / u;  // (M u)_i / u_i
      lo = std::min(lo, q);
      hi = std::max(hi, q);
      uu += u * u;
      mm += static_cast<double>(w[i]) * w[i];
    }
    r.iterations = it;
    r.estimate = std::sqrt(mm / uu);
    r.lower = lo;
    r.upper = hi;
    // Rows of zero albedo hold the lower bound at 0 for good: stop also when
    // the upper bound has settled.
    if (hi - lo <= tolerance * hi || std::abs(hi - previous_upper) <= 1e-3 * tolerance * hi) {
      r.converged = true;
      break;
    }
    previous_upper = hi;
    // The next v is T v: power iteration on T, whose eigenvalues
    // lambda / (1 - lambda) spread the Perron root further from the rest
    // than M's do.
    float w_max = 0.0f;
    for (std::size_t i = 0; i < n; ++i) w_max = std::max(w_max, w[i]);
    if (!(w_max > 0.0f)) {
      r.converged = true;  // T v = 0 for v > 0: T = 0, rho = 0
      break;
    }
    for (std::size_t i = 0; i < n; ++i) v[i] = std::max(w[i], 0.0f) / w_max + kFloor;
  }
  return r;
}

}  // namespace bounce
