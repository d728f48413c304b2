#include "transport/inverse_transport.h"

#include <lapacke.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "base/error.h"
#include "transport/blas_int.h"
#include "transport/symmetric_transport.h"
#include "transport/text_format.h"

static_assert(sizeof(lapack_int) == sizeof(int), "LAPACKE built with 64-bit integers");

namespace bounce {

namespace {

// LAPACKE's _work entry points, without the plain ones' single-threaded NaN
// scan of the whole input on every call (the LU again for each
// right-hand-side block): the transport refuses NaN and Inf in F before the
// system is built (transport.cpp) and checks T after.
template <class Real>
struct Lapack;

template <>
struct Lapack<float> {
  static lapack_int getrf(int n, float* a, lapack_int* ipiv) {
    return LAPACKE_sgetrf_work(LAPACK_COL_MAJOR, n, n, a, n, ipiv);
  }
  static lapack_int gecon(int n, const float* a, double anorm, double* rcond) {
    float r = 0.0f;
    std::vector<float> work(4 * static_cast<std::size_t>(n));
    std::vector<lapack_int> iwork(static_cast<std::size_t>(n));
    const lapack_int info = LAPACKE_sgecon_work(
        LAPACK_COL_MAJOR, '1', n, a, n, static_cast<float>(anorm), &r, work.data(), iwork.data());
    *rcond = r;
    return info;
  }
  static lapack_int getrs(int n, int nrhs, const float* a, const lapack_int* ipiv, float* b) {
    return LAPACKE_sgetrs_work(LAPACK_COL_MAJOR, 'N', n, nrhs, a, n, ipiv, b, n);
  }
};

template <>
struct Lapack<double> {
  static lapack_int getrf(int n, double* a, lapack_int* ipiv) {
    return LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, n, n, a, n, ipiv);
  }
  static lapack_int gecon(int n, const double* a, double anorm, double* rcond) {
    std::vector<double> work(4 * static_cast<std::size_t>(n));
    std::vector<lapack_int> iwork(static_cast<std::size_t>(n));
    return LAPACKE_dgecon_work(LAPACK_COL_MAJOR, '1', n, a, n, anorm, rcond, work.data(),
                               iwork.data());
  }
  static lapack_int getrs(int n, int nrhs, const double* a, const lapack_int* ipiv, double* b) {
    return LAPACKE_dgetrs_work(LAPACK_COL_MAJOR, 'N', n, nrhs, a, n, ipiv, b, n);
  }
};

void check_info(lapack_int info, const char* routine) {
  if (info < 0)
    throw Error("transport",
                text_format("%s rejected argument %d", routine, static_cast<int>(-info)));
  if (info > 0)
    throw Error("transport",
                text_format("%s: I - diag(albedo) F is exactly singular (zero pivot %d): light "
                            "would grow without bound; check form-factor row sums and albedo",
                            routine, static_cast<int>(info)));
}

template <class Real>
struct Factorisation {
  MatrixBuffer<Real> lu;
  std::vector<lapack_int> ipiv;
  double condition = 0.0;
};

// LU of I - M^T (the row-major I - M read column-major) and its condition.
template <class Real, class Source>
Factorisation<Real> factorise(const Source* m, std::size_t n, double anorm) {
  const int k = blas_dim(n, "LAPACKE_?getrf");
  Factorisation<Real> f;
  f.lu.resize(n * n);
  for (std::size_t i = 0; i < n * n; ++i) f.lu[i] = -static_cast<Real>(m[i]);
  for (std::size_t d = 0; d < n; ++d) f.lu[d * n + d] += Real(1);
  f.ipiv.resize(n);
  check_info(Lapack<Real>::getrf(k, f.lu.data(), f.ipiv.data()), "LAPACKE_?getrf");
  double rcond = 0.0;
  check_info(Lapack<Real>::gecon(k, f.lu.data(), anorm, &rcond), "LAPACKE_?gecon");
  f.condition = rcond > 0.0 ? 1.0 / rcond : std::numeric_limits<double>::infinity();
  return f;
}

// Overwrites rhs (column-major n x n, i.e. the row-major M) with the solution,
// block by block so progress and cancellation are heard during the solve.
// Float rhs with a double factorisation: each block is solved in a double
// copy and rounded back, so no n x n double right-hand side is ever held.
template <class Real>
void solve(const Factorisation<Real>& f, float* rhs, std::size_t n, const InverseOptions& options) {
  const int k = blas_dim(n, "LAPACKE_?getrs");
  const std::size_t blocks = std::clamp<std::size_t>(options.solve_blocks, 1, n);
  std::vector<Real> block;
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t first = n * b / blocks, last = n * (b + 1) / blocks;
    if (last > first) {
      float* x = rhs + first * n;
      const std::size_t count = (last - first) * n;
      Real* xr = nullptr;
      if constexpr (std::is_same_v<Real, float>) {
        xr = x;
      } else {
        block.assign(x, x + count);
        xr = block.data();
      }
      check_info(
          Lapack<Real>::getrs(k, static_cast<int>(last - first), f.lu.data(), f.ipiv.data(), xr),
          "LAPACKE_?getrs");
      if constexpr (!std::is_same_v<Real, float>)
        for (std::size_t i = 0; i < count; ++i) x[i] = static_cast<float>(block[i]);
    }
    if (options.tick) options.tick();
  }
}

double inf_norm_of_identity_minus(const float* m, std::size_t n) {
  double norm = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double row = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const double v = static_cast<double>(m[i * n + j]);
      row += i == j ? std::abs(1.0 - v) : std::abs(v);
    }
    norm = std::max(norm, row);
  }
  return norm;
}

}  // namespace

double condition_lower_bound(const float* m, std::size_t n, double spectral_radius) {
  if (spectral_radius < 0.0) return 0.0;  // not known
  if (!(spectral_radius < 1.0)) return std::numeric_limits<double>::infinity();
  return inf_norm_of_identity_minus(m, n) / (1.0 - spectral_radius);
}

PrecisionChoice precision_before_factorising(double condition_lower_bound,
                                             const InverseOptions& options) {
  PrecisionChoice c;
  const double limit = options.float32_error_limit;
  if (options.force) {
    c.precision = *options.force;
    c.why = text_format("%s forced", precision_name(*options.force));
  } else if (condition_lower_bound * FLT_EPSILON > limit) {
    c.precision = TransportPrecision::Float64;
    c.why = text_format(
        "float64: condition >= ||I-M|| / (1 - rho) = %.3g before factorising, so float32's "
        "error estimate kappa * eps >= %.2g exceeds %.0e",
        condition_lower_bound, condition_lower_bound * FLT_EPSILON, limit);
  }
  return c;
}

TransportPrecision predicted_precision(double condition_lower_bound,
                                       const InverseOptions& options) {
  return precision_before_factorising(condition_lower_bound, options).precision;
}

double solve_cost_in_gemms(InverseMethod method, TransportPrecision precision) {
  if (method == InverseMethod::Cholesky)
    return precision == TransportPrecision::Float64 ? 2.5 : 1.2;
  return precision == TransportPrecision::Float64 ? 3.5 : 1.5;
}

const char* precision_name(TransportPrecision p) {
  return p == TransportPrecision::Float64 ? "float64" : "float32";
}

const char* method_name(InverseMethod m) {
  return m == InverseMethod::Cholesky ? "Cholesky" : "LU";
}

InverseTransport solve_infinite_bounces(std::vector<float> m, std::size_t n, double spectral_radius,
                                        const InverseOptions& options) {
  if (m.size() != n * n) throw Error("transport", "solve_infinite_bounces: size does not match n");
  InverseTransport r = solve_infinite_bounces_in_place(m.data(), n, spectral_radius, options);
  if (n > 0) r.t = std::move(m);
  return r;
}

namespace {

double lu_flops(std::size_t n) {
  const double d = static_cast<double>(n);
  return 2.0 * d * d * d / 3.0;  // ?getrf; ?getrs adds 2 n^3 for n right-hand sides
}

InverseTransport solve_by_lu(float* m, std::size_t n, double spectral_radius,
                             const InverseOptions& options) {
  InverseTransport r;
  r.method = InverseMethod::LU;
  const double nn = static_cast<double>(n);
  // ||I - M||_inf, also the anorm ?gecon needs for the column-major I - M^T.
  const double anorm = inf_norm_of_identity_minus(m, n);
  if (spectral_radius >= 0.0)
    r.condition_lower_bound = spectral_radius < 1.0 ? anorm / (1.0 - spectral_radius)
                                                    : std::numeric_limits<double>::infinity();
  const double limit = options.float32_error_limit;

  PrecisionChoice choice = precision_before_factorising(r.condition_lower_bound, options);
  bool use_float64 = choice.precision == TransportPrecision::Float64;
  r.why = std::move(choice.why);

  if (!use_float64) {
    Factorisation<float> f = factorise<float>(m, n, anorm);
    r.flops += lu_flops(n);
    r.condition = f.condition;
    if (!options.force && f.condition * FLT_EPSILON > limit) {
      use_float64 = true;
      r.refactorised = true;
      r.why = text_format(
          "float64: float32 LU's condition estimate %.3g gives kappa * eps = %.2g > %.0e "
          "(the lower bound %.3g had allowed float32); refactorised",
          f.condition, f.condition * FLT_EPSILON, limit, r.condition_lower_bound);
    } else {
      if (!options.force)
        r.why = text_format("float32: condition estimate %.3g gives kappa * eps = %.2g <= %.0e",
                            f.condition, f.condition * FLT_EPSILON, limit);
      if (options.tick) options.tick();
      solve(f, m, n, options);
      r.flops += 2.0 * nn * nn * nn;
      r.precision = TransportPrecision::Float32;
      return r;
    }
  }

  // float64: the factorisation from the float M (exact in double), the
  // right-hand side converted block by block in solve().
  Factorisation<double> f = factorise<double>(m, n, anorm);
  r.flops += lu_flops(n);
  r.condition = f.condition;
  check_float64_condition(f.condition);
  if (options.tick) options.tick();
  solve(f, m, n, options);
  r.flops += 2.0 * nn * nn * nn;
  r.precision = TransportPrecision::Float64;
  return r;
}

}  // namespace

InverseTransport solve_infinite_bounces_in_place(float* m, std::size_t n, double spectral_radius,
                                                 const InverseOptions& options) {
  if (n == 0) return {};
  if (options.area.empty() && options.albedo.empty())
    return solve_by_lu(m, n, spectral_radius, options);
  CholeskyAttempt attempt = solve_by_cholesky(m, n, spectral_radius, options);
  if (attempt.result) return std::move(*attempt.result);
  InverseTransport r = solve_by_lu(m, n, spectral_radius, options);
  r.lu_reason = std::move(attempt.why_not);
  r.flops += attempt.flops;
  return r;
}

}  // namespace bounce
