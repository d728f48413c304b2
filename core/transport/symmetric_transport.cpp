#include "transport/symmetric_transport.h"

#include <cblas.h>
#include <lapacke.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "base/error.h"
#include "base/mapped_buffer.h"
#include "transport/blas_int.h"
#include "transport/text_format.h"

namespace bounce {

namespace {

// float64 results with fewer than two correct digits are refused, as by the LU.
constexpr double kFloat64ErrorLimit = 1e-2;
// Tiles of the transposing pass that builds S: 64 x 64 floats of M and of
// M^T stay in L1/L2 together.
constexpr std::size_t kTile = 64;

// The factorisation, condition estimate and solves call LAPACKE's _work
// entry points: the plain ones first scan their whole input for NaN on one
// thread, every call (L again for each right-hand-side block), which this
// solve does not need: the transport refuses NaN and Inf in F before S is
// built (transport.cpp) and checks T after.
template <class Real>
struct Lapack;

template <>
struct Lapack<float> {
  static lapack_int potrf(int n, float* a) {
    return LAPACKE_spotrf_work(LAPACK_COL_MAJOR, 'L', n, a, n);
  }
  static lapack_int pocon(int n, const float* a, double anorm, double* rcond) {
    float r = 0.0f;
    std::vector<float> work(3 * static_cast<std::size_t>(n));
    std::vector<lapack_int> iwork(static_cast<std::size_t>(n));
    const lapack_int info = LAPACKE_spocon_work(
        LAPACK_COL_MAJOR, 'L', n, a, n, static_cast<float>(anorm), &r, work.data(), iwork.data());
    *rcond = r;
    return info;
  }
  static lapack_int potrs(int n, int nrhs, const float* a, float* b, int ldb) {
    return LAPACKE_spotrs_work(LAPACK_COL_MAJOR, 'L', n, nrhs, a, n, b, ldb);
  }
  // c += a b, column-major.
  static void gemm(int m, int n, int k, const float* a, int lda, const float* b, int ldb, float* c,
                   int ldc) {
    cblas_sgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, m, n, k, 1.0f, a, lda, b, ldb, 1.0f, c,
                ldc);
  }
};

template <>
struct Lapack<double> {
  static lapack_int potrf(int n, double* a) {
    return LAPACKE_dpotrf_work(LAPACK_COL_MAJOR, 'L', n, a, n);
  }
  static lapack_int pocon(int n, const double* a, double anorm, double* rcond) {
    std::vector<double> work(3 * static_cast<std::size_t>(n));
    std::vector<lapack_int> iwork(static_cast<std::size_t>(n));
    return LAPACKE_dpocon_work(LAPACK_COL_MAJOR, 'L', n, a, n, anorm, rcond, work.data(),
                               iwork.data());
  }
  static lapack_int potrs(int n, int nrhs, const double* a, double* b, int ldb) {
    return LAPACKE_dpotrs_work(LAPACK_COL_MAJOR, 'L', n, nrhs, a, n, b, ldb);
  }
  static void gemm(int m, int n, int k, const double* a, int lda, const double* b, int ldb,
                   double* c, int ldc) {
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, m, n, k, 1.0, a, lda, b, ldb, 1.0, c,
                ldc);
  }
};

void check_arguments(lapack_int info, const char* routine) {
  if (info < 0)
    throw Error("transport",
                text_format("%s rejected argument %d", routine, static_cast<int>(-info)));
}

// P (albedo > 0, in patch order) and Z (albedo 0), and E = sqrt(rho / A) over P.
struct Split {
  std::vector<std::size_t> lit, dark;
  std::vector<double> e;
};

std::optional<Split> split_patches(const InverseOptions& o, std::size_t n, std::string& why_not) {
  if (o.area.size() != n || o.albedo.size() != n) {
    why_not =
        text_format("%zu areas and %zu albedos for %zu patches", o.area.size(), o.albedo.size(), n);
    return std::nullopt;
  }
  Split s;
  for (std::size_t p = 0; p < n; ++p) {
    if (!(o.albedo[p] > 0.0f)) {
      s.dark.push_back(p);
      continue;
    }
    if (!(o.area[p] > 0.0f)) {
      why_not = text_format("patch %zu has albedo %g but area %g", p,
                            static_cast<double>(o.albedo[p]), static_cast<double>(o.area[p]));
      return std::nullopt;
    }
    s.lit.push_back(p);
    s.e.push_back(std::sqrt(static_cast<double>(o.albedo[p]) / static_cast<double>(o.area[p])));
  }
  return s;
}

struct System {
  double norm1 = 0.0;      // ||S||_1, for ?pocon and the lower bound
  double asymmetry = 0.0;  // of B before symmetrising
};

// S = I - (B + B^T) / 2 over P, column-major, both triangles, with
// B_ij = e_i M^T_pq / e_j = e_i M_qp / e_j (p = P[i], q = P[j]), in float64
// from the float M, rounded once to Real.
template <class Real>
System build_system(const float* m, std::size_t n, const Split& s, MatrixBuffer<Real>& a) {
  const std::size_t np = s.lit.size();
  a.assign(np * np, Real(0));
  const auto tiles = static_cast<std::int64_t>((np + kTile - 1) / kTile);
  double asymmetry = 0.0;
#pragma omp parallel for schedule(dynamic, 1) reduction(max : asymmetry)
  for (std::int64_t jt = 0; jt < tiles; ++jt) {
    const std::size_t j0 = static_cast<std::size_t>(jt) * kTile, j1 = std::min(np, j0 + kTile);
    for (std::size_t i0 = j0; i0 < np; i0 += kTile) {
      const std::size_t i1 = std::min(np, i0 + kTile);
      for (std::size_t j = j0; j < j1; ++j) {
        const std::size_t q = s.lit[j];
        for (std::size_t i = std::max(i0, j); i < i1; ++i) {
          const std::size_t p = s.lit[i];
          const double bij = s.e[i] * static_cast<double>(m[q * n + p]) / s.e[j];
          const double bji = s.e[j] * static_cast<double>(m[p * n + q]) / s.e[i];
          const double scale = std::max(std::abs(bij), std::abs(bji));
          if (scale > 0.0) asymmetry = std::max(asymmetry, std::abs(bij - bji) / scale);
          const auto v = static_cast<Real>((i == j ? 1.0 : 0.0) - 0.5 * (bij + bji));
          a[j * np + i] = v;
          a[i * np + j] = v;
        }
      }
    }
  }
  System sys;
  sys.asymmetry = asymmetry;
  for (std::size_t j = 0; j < np; ++j) {
    double column = 0.0;
    for (std::size_t i = 0; i < np; ++i) column += std::abs(static_cast<double>(a[j * np + i]));
    sys.norm1 = std::max(sys.norm1, column);
  }
  return sys;
}

// M^T_ZP, column-major |Z| x |P|: (k, i) = M_pz with p = P[i], z = Z[k].
template <class Real>
std::vector<Real> dark_rows(const float* m, std::size_t n, const Split& s) {
  const std::size_t nz = s.dark.size();
  std::vector<Real> out(nz * s.lit.size());
  for (std::size_t i = 0; i < s.lit.size(); ++i)
    for (std::size_t k = 0; k < nz; ++k) out[i * nz + k] = m[s.lit[i] * n + s.dark[k]];
  return out;
}

// One right-hand side column x (n values, patch order) to P order scaled by
// E, then Z order unscaled; `back` undoes it on the solution.
template <class Real>
void gather(Real* x, const Split& s, std::vector<Real>& tmp) {
  const std::size_t np = s.lit.size();
  if (s.dark.empty()) {
    for (std::size_t i = 0; i < np; ++i) x[i] = static_cast<Real>(x[i] * s.e[i]);
    return;
  }
  tmp.assign(x, x + np + s.dark.size());  // n values
  for (std::size_t i = 0; i < np; ++i) x[i] = static_cast<Real>(tmp[s.lit[i]] * s.e[i]);
  for (std::size_t k = 0; k < s.dark.size(); ++k) x[np + k] = tmp[s.dark[k]];
}

template <class Real>
void unscale(Real* x, const Split& s) {
  for (std::size_t i = 0; i < s.lit.size(); ++i) x[i] = static_cast<Real>(x[i] / s.e[i]);
}

template <class Real>
void scatter(Real* x, const Split& s, std::vector<Real>& tmp) {
  if (s.dark.empty()) return;
  const std::size_t np = s.lit.size();
  tmp.assign(x, x + np + s.dark.size());
  for (std::size_t i = 0; i < np; ++i) x[s.lit[i]] = tmp[i];
  for (std::size_t k = 0; k < s.dark.size(); ++k) x[s.dark[k]] = tmp[np + k];
}

// Overwrites m (column-major M^T, all n columns) with T^T, block by block so
// progress and cancellation are heard; float64 solves each block in a
// double copy. Returns the flops.
template <class Real>
double solve(const MatrixBuffer<Real>& l, const Split& s, float* m, std::size_t n,
             const InverseOptions& options) {
  const int np = blas_dim(s.lit.size(), "LAPACKE_?potrs");
  const int nz = blas_dim(s.dark.size(), "cblas_?gemm");
  const int ld = blas_dim(n, "LAPACKE_?potrs");
  const std::vector<Real> mzp = dark_rows<Real>(m, n, s);
  const std::size_t blocks = std::clamp<std::size_t>(options.solve_blocks, 1, n);
  std::vector<Real> block, tmp;
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t first = n * b / blocks, last = n * (b + 1) / blocks;
    const std::size_t cols = last - first;
    if (cols > 0) {
      float* x = m + first * n;
      Real* xr = nullptr;
      if constexpr (std::is_same_v<Real, float>) {
        xr = x;
      } else {
        block.assign(x, x + cols * n);
        xr = block.data();
      }
      for (std::size_t c = 0; c < cols; ++c) gather(xr + c * n, s, tmp);
      const int k = static_cast<int>(cols);
      check_arguments(Lapack<Real>::potrs(np, k, l.data(), xr, ld), "LAPACKE_?potrs");
      for (std::size_t c = 0; c < cols; ++c) unscale(xr + c * n, s);
      if (nz > 0 && np > 0) Lapack<Real>::gemm(nz, k, np, mzp.data(), nz, xr, ld, xr + np, ld);
      for (std::size_t c = 0; c < cols; ++c) scatter(xr + c * n, s, tmp);
      if constexpr (!std::is_same_v<Real, float>)
        for (std::size_t i = 0; i < cols * n; ++i) x[i] = static_cast<float>(block[i]);
    }
    if (options.tick) options.tick();
  }
  const auto p = static_cast<double>(s.lit.size()), z = static_cast<double>(s.dark.size());
  const auto nn = static_cast<double>(n);
  return 2.0 * p * p * nn + 2.0 * z * p * nn;
}

template <class Real>
struct Factor {
  MatrixBuffer<Real> l;
  System system;
  lapack_int breakdown = 0;  // column (from 1) where ?potrf found S not positive definite
  double condition = 0.0;
};

template <class Real>
Factor<Real> build(const float* m, std::size_t n, const Split& s) {
  Factor<Real> f;
  f.system = build_system(m, n, s, f.l);
  return f;
}

// ?potrf, then ?pocon when it succeeded.
template <class Real>
void factorise(Factor<Real>& f, const Split& s, double& flops) {
  const int k = blas_dim(s.lit.size(), "LAPACKE_?potrf");
  const lapack_int info = Lapack<Real>::potrf(k, f.l.data());
  const double p = static_cast<double>(s.lit.size());
  flops += p * p * p / 3.0;
  check_arguments(info, "LAPACKE_?potrf");
  if (info > 0) {
    f.breakdown = info;
    return;
  }
  double rcond = 0.0;
  check_arguments(Lapack<Real>::pocon(k, f.l.data(), f.system.norm1, &rcond), "LAPACKE_?pocon");
  f.condition = rcond > 0.0 ? 1.0 / rcond : std::numeric_limits<double>::infinity();
}

std::string asymmetric(double asymmetry, double limit) {
  return text_format(
      "A F is not symmetric: relative asymmetry up to %.2g > %.0e (the form factors are not "
      "balanced, e.g. 'closure_rays' 0)",
      asymmetry, limit);
}

template <class Real>
void finish(const Factor<Real>& f, const Split& s, float* m, std::size_t n,
            const InverseOptions& options, InverseTransport r, CholeskyAttempt& out) {
  if (options.tick) options.tick();
  out.flops += solve(f.l, s, m, n, options);
  r.precision =
      std::is_same_v<Real, float> ? TransportPrecision::Float32 : TransportPrecision::Float64;
  r.flops = out.flops;
  out.result = std::move(r);
}

enum class Next { Float32, Float64, Lu };

// The precision rule on the float32 system f (built, not yet factorised):
// factorises it unless the lower bound already asks for float64, and says
// how to go on; r.why records the rule as applied.
Next float32_verdict(Factor<float>& f, const Split& s, double spectral_radius,
                     const InverseOptions& options, InverseTransport& r, CholeskyAttempt& out) {
  const double limit = options.float32_error_limit;
  if (spectral_radius >= 0.0)
    r.condition_lower_bound = spectral_radius < 1.0 ? f.system.norm1 / (1.0 - spectral_radius)
                                                    : std::numeric_limits<double>::infinity();
  PrecisionChoice choice = precision_before_factorising(r.condition_lower_bound, options);
  r.why = std::move(choice.why);
  if (choice.precision == TransportPrecision::Float64) return Next::Float64;
  factorise(f, s, out.flops);
  if (f.breakdown > 0) {
    const auto column = static_cast<int>(f.breakdown);
    if (options.force) {
      out.why_not =
          text_format("float32 Cholesky broke down at column %d (float32 forced)", column);
      return Next::Lu;
    }
    r.refactorised = true;
    r.why = text_format(
        "float64: float32 Cholesky broke down at column %d, S is too close to singular for "
        "float32; refactorised",
        column);
    return Next::Float64;
  }
  r.condition = f.condition;
  const double error = f.condition * FLT_EPSILON;
  if (!options.force && error > limit) {
    r.refactorised = true;
    r.why = text_format(
        "float64: float32 Cholesky's condition estimate %.3g gives kappa * eps = %.2g > %.0e; "
        "refactorised",
        f.condition, error, limit);
    return Next::Float64;
  }
  if (!options.force)
    r.why = text_format("float32: condition estimate %.3g gives kappa * eps = %.2g <= %.0e",
                        f.condition, error, limit);
  return Next::Float32;
}

}  // namespace

void check_float64_condition(double condition) {
  if (condition * DBL_EPSILON > kFloat64ErrorLimit)
    throw Error("transport", text_format("I - diag(albedo) F is numerically singular (condition "
                                         "%.3g): check form-factor row sums and albedo",
                                         condition));
}

CholeskyAttempt solve_by_cholesky(float* m, std::size_t n, double spectral_radius,
                                  const InverseOptions& options) {
  CholeskyAttempt out;
  const std::optional<Split> split = split_patches(options, n, out.why_not);
  if (!split) return out;
  InverseTransport r;
  r.method = InverseMethod::Cholesky;
  if (split->lit.empty()) {  // every albedo 0: M = 0 and T = M, nothing to solve
    r.condition = 1.0;
    r.why = "float32: every albedo is 0, T = M = 0";
    const std::size_t ticks = 1 + std::clamp<std::size_t>(options.solve_blocks, 1, n);
    for (std::size_t i = 0; options.tick && i < ticks; ++i) options.tick();  // as a solve would
    out.result = std::move(r);
    return out;
  }
  {
    Factor<float> f = build<float>(m, n, *split);
    r.asymmetry = f.system.asymmetry;
    if (f.system.asymmetry > options.asymmetry_limit) {
      out.why_not = asymmetric(f.system.asymmetry, options.asymmetry_limit);
      return out;
    }
    const Next next = float32_verdict(f, *split, spectral_radius, options, r, out);
    if (next == Next::Lu) return out;
    if (next == Next::Float32) {
      finish(f, *split, m, n, options, std::move(r), out);
      return out;
    }
  }  // the float32 system is released before the float64 one is built

  Factor<double> f = build<double>(m, n, *split);
  factorise(f, *split, out.flops);
  if (f.breakdown > 0) {
    out.why_not = text_format(
        "S = I - E A F E is not positive definite (float64 Cholesky broke down at column %d): "
        "the spectral radius of diag(albedo) F is 1 or more",
        static_cast<int>(f.breakdown));
    return out;
  }
  r.condition = f.condition;
  check_float64_condition(f.condition);
  finish(f, *split, m, n, options, std::move(r), out);
  return out;
}

}  // namespace bounce
