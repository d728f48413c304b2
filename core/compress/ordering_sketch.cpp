#include "compress/ordering_sketch.h"

#include <cblas.h>
#include <lapacke.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/error.h"
#include "base/random.h"

static_assert(sizeof(blasint) == sizeof(int), "OpenBLAS built with 64-bit integers");
static_assert(sizeof(lapack_int) == sizeof(int), "LAPACKE built with 64-bit integers");

namespace bounce {
namespace {

int dim(std::size_t v) {
  if (v > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw Error("ordering",
                "sketch: dimension " + std::to_string(v) + " exceeds the 32-bit BLAS interface");
  return static_cast<int>(v);
}

// +-1 entries, `rows` x k, one random stream per row so the matrix does not
// depend on threads.
std::vector<float> rademacher(std::size_t rows, std::size_t k, std::uint64_t seed,
                              std::uint64_t stream0) {
  std::vector<float> m(rows * k);
#pragma omp parallel for schedule(static) if (rows * k >= (std::size_t{1} << 18))
  for (std::ptrdiff_t r = 0; r < static_cast<std::ptrdiff_t>(rows); ++r) {
    Rng rng(seed, stream0 + static_cast<std::uint64_t>(r));
    std::uint64_t bits = 0;
    for (std::size_t t = 0; t < k; ++t) {
      if (t % 64 == 0) bits = rng.next();
      m[static_cast<std::size_t>(r) * k + t] = (bits >> (t % 64)) & 1u ? 1.0f : -1.0f;
    }
  }
  return m;
}

// Reads the image in panels of rows, converted to float and split by channel
// (channel c of panel row r, column j at panel[(c * rows + r) * n + j]) so
// that both A and A^T products are plain row-major sgemm calls.
class PanelReader {
 public:
  PanelReader(const std::uint8_t* image, std::size_t n, std::size_t channels, bool zero_is_hole)
      : image_(image), n_(n), channels_(channels), hole_(zero_is_hole ? 255.0f : 0.0f) {
    // ~24 MB of floats per panel: big enough for efficient sgemm, small
    // enough to stay far from the memory budget at n = 16384.
    rows_ = std::clamp<std::size_t>((std::size_t{1} << 21) / std::max<std::size_t>(n, 1), 16, n);
    buffer_.resize(channels * rows_ * n);
  }
  std::size_t panel_rows() const { return rows_; }

  // Converts rows [r0, r0 + rows); returns the float panel.
  const float* load(std::size_t r0, std::size_t rows) {
    const std::size_t n = n_, ch = channels_;
    const bool parallel = rows * n * ch >= (std::size_t{1} << 20);
#pragma omp parallel for schedule(static) if (parallel)
    for (std::ptrdiff_t r = 0; r < static_cast<std::ptrdiff_t>(rows); ++r) {
      const std::uint8_t* src = image_ + (r0 + static_cast<std::size_t>(r)) * n * ch;
      for (std::size_t c = 0; c < ch; ++c) {
        float* dst = buffer_.data() + (c * rows + static_cast<std::size_t>(r)) * n;
        for (std::size_t j = 0; j < n; ++j) {
          const std::uint8_t v = src[j * ch + c];
          dst[j] = v == 0 ? hole_ : static_cast<float>(v);
        }
      }
    }
    return buffer_.data();
  }

 private:
  const std::uint8_t* image_;
  std::size_t n_, channels_, rows_;
  float hole_;  // what code 0 reads as
  std::vector<float> buffer_;
};

}  // namespace

Sketch principal_sketch(const std::uint8_t* image, std::size_t n, std::size_t channels,
                        const SketchSettings& settings) {
  if (channels == 0) throw Error("ordering", "sketch: no channels");
  if (settings.dims == 0) throw Error("ordering", "sketch: dims must be at least 1");
  Sketch out;
  out.n = n;
  // The centred rows span at most n - 1 dimensions.
  if (n < 2) return out;
  const std::size_t k = std::min(settings.dims + settings.oversampling, n - 1);
  const std::size_t dims = std::min(settings.dims, k);
  const bool cols = settings.use_columns;
  // Threads for images big enough to pay for fork/joins on a busy machine.
  const bool parallel = n * n * channels >= (std::size_t{1} << 20);
  const int ni = dim(n), ki = dim(k);

  // Omega for the row part (channel c: n x k block) and the column part.
  const std::vector<float> omega_a = rademacher(channels * n, k, settings.seed, 0);
  const std::vector<float> omega_t =
      cols ? rademacher(channels * n, k, settings.seed, channels * n) : std::vector<float>{};

  PanelReader reader(image, n, channels, settings.zero_is_hole);
  const std::size_t panel = reader.panel_rows();

  // Pass 1: Y = M Omega, plus what the captured-energy figure needs: the sum
  // of squares of all codes and the row and column means of each channel.
  std::vector<float> y(n * k, 0.0f);
  std::vector<double> row_sum(n * channels, 0.0), col_sum(channels * n, 0.0);
  double sum_sq = 0.0;
  for (std::size_t r0 = 0; r0 < n; r0 += panel) {
    const std::size_t rows = std::min(panel, n - r0);
    const int ri = dim(rows);
    const float* f = reader.load(r0, rows);
    std::vector<double> panel_sq(rows, 0.0);
#pragma omp parallel for schedule(static) if (parallel)
    for (std::ptrdiff_t r = 0; r < static_cast<std::ptrdiff_t>(rows); ++r) {
      const std::size_t ru = static_cast<std::size_t>(r);
      double sq = 0.0;
      for (std::size_t c = 0; c < channels; ++c) {
        const float* row = f + (c * rows + ru) * n;
        double s = 0.0;
        for (std::size_t j = 0; j < n; ++j) {
          s += row[j];
          sq += static_cast<double>(row[j]) * row[j];
        }
        row_sum[(r0 + ru) * channels + c] = s;
      }
      panel_sq[ru] = sq;
    }
    for (const double v : panel_sq) sum_sq += v;
    // Column sums by stripes of columns: each thread owns its stripe and reads
    // the panel row by row.
    constexpr std::size_t kStripe = 512;
#pragma omp parallel for schedule(static) if (parallel)
    for (std::ptrdiff_t s = 0; s < static_cast<std::ptrdiff_t>((n + kStripe - 1) / kStripe); ++s) {
      const std::size_t j0 = static_cast<std::size_t>(s) * kStripe, j1 = std::min(n, j0 + kStripe);
      for (std::size_t c = 0; c < channels; ++c)
        for (std::size_t r = 0; r < rows; ++r) {
          const float* row = f + (c * rows + r) * n;
          for (std::size_t j = j0; j < j1; ++j) col_sum[c * n + j] += row[j];
        }
    }

    for (std::size_t c = 0; c < channels; ++c) {
      const float* fc = f + c * rows * n;
      // Rows r0.. of Y: the row part of M.
      cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, ri, ki, ni, 1.0f, fc, ni,
                  omega_a.data() + c * n * k, ki, 1.0f, y.data() + r0 * k, ki);
      // All of Y: the column part (row j of the panel is column j of M^T).
      if (cols)
        cblas_sgemm(CblasRowMajor, CblasTrans, CblasNoTrans, ni, ki, ri, 1.0f, fc, ni,
                    omega_t.data() + (c * n + r0) * k, ki, 1.0f, y.data(), ki);
    }
  }

  // Centre Y (= centre M: the mean row of M times Omega is the mean row of Y)
  // and orthonormalise its columns in double; Q is column-major while built.
  std::vector<double> q(k * n);
  for (std::size_t t = 0; t < k; ++t) {
    double mean = 0.0;
    for (std::size_t i = 0; i < n; ++i) mean += y[i * k + t];
    mean /= static_cast<double>(n);
    for (std::size_t i = 0; i < n; ++i) q[t * n + i] = y[i * k + t] - mean;
  }
  for (std::size_t t = 0; t < k; ++t) {
    double* v = q.data() + t * n;
    double norm0 = 0.0;
    for (std::size_t i = 0; i < n; ++i) norm0 += v[i] * v[i];
    norm0 = std::sqrt(norm0);
    // Twice is enough ("twice is enough", Kahan / Parlett) for a basis that
    // is orthonormal to rounding even when Y is badly conditioned.
    for (int repeat = 0; repeat < 2; ++repeat)
      for (std::size_t s = 0; s < t; ++s) {
        const double* u = q.data() + s * n;
        double d = 0.0;
        for (std::size_t i = 0; i < n; ++i) d += u[i] * v[i];
        for (std::size_t i = 0; i < n; ++i) v[i] -= d * u[i];
      }
    double norm = 0.0;
    for (std::size_t i = 0; i < n; ++i) norm += v[i] * v[i];
    norm = std::sqrt(norm);
    // A direction Y does not really have (M of lower rank than k) is dropped:
    // a zero column contributes nothing below.
    const double scale = norm > 1e-9 * norm0 && norm > 0.0 ? 1.0 / norm : 0.0;
    for (std::size_t i = 0; i < n; ++i) v[i] *= scale;
  }
  std::vector<float> qf(n * k);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t t = 0; t < k; ++t) qf[i * k + t] = static_cast<float>(q[t * n + i]);

  // Pass 2: B = Q^T M; G = B B^T accumulated in double. The column part of B
  // for panel rows is final at once (W = F_c Q); the row part sums over all
  // panels first.
  std::vector<float> b_rows(channels * k * n, 0.0f), w(panel * k);
  std::vector<double> g(k * k, 0.0);
  for (std::size_t r0 = 0; r0 < n; r0 += panel) {
    const std::size_t rows = std::min(panel, n - r0);
    const int ri = dim(rows);
    const float* f = reader.load(r0, rows);
    for (std::size_t c = 0; c < channels; ++c) {
      const float* fc = f + c * rows * n;
      cblas_sgemm(CblasRowMajor, CblasTrans, CblasNoTrans, ki, ni, ri, 1.0f, qf.data() + r0 * k, ki,
                  fc, ni, 1.0f, b_rows.data() + c * k * n, ni);
      if (cols) {
        cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, ri, ki, ni, 1.0f, fc, ni, qf.data(),
                    ki, 0.0f, w.data(), ki);
        for (std::size_t r = 0; r < rows; ++r)
          for (std::size_t t = 0; t < k; ++t)
            for (std::size_t u = t; u < k; ++u)
              g[t * k + u] += static_cast<double>(w[r * k + t]) * w[r * k + u];
      }
    }
  }
#pragma omp parallel for schedule(dynamic, 1) if (parallel)
  for (std::ptrdiff_t t = 0; t < static_cast<std::ptrdiff_t>(k); ++t) {
    const std::size_t tu = static_cast<std::size_t>(t);
    for (std::size_t u = tu; u < k; ++u) {
      double s = 0.0;
      for (std::size_t c = 0; c < channels; ++c) {
        const float* bt = b_rows.data() + (c * k + tu) * n;
        const float* bu = b_rows.data() + (c * k + u) * n;
        for (std::size_t j = 0; j < n; ++j) s += static_cast<double>(bt[j]) * bu[j];
      }
      g[tu * k + u] += s;
    }
  }
  for (std::size_t t = 0; t < k; ++t)
    for (std::size_t u = 0; u < t; ++u) g[t * k + u] = g[u * k + t];

  // G = U diag(lambda) U^T; LAPACK returns ascending eigenvalues, the
  // principal axis is the last one.
  std::vector<double> lambda(k);
  const lapack_int info =
      LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'V', 'U', ki, g.data(), ki, lambda.data());
  if (info != 0)
    throw Error("ordering", "sketch: dsyev failed (info " + std::to_string(info) + ")");

  out.dims = dims;
  out.coords.assign(n * dims, 0.0f);
  out.variances.resize(dims);
  std::vector<double> axis(k * dims);  // U column, scaled by sqrt(lambda)
  double kept = 0.0;
  for (std::size_t a = 0; a < dims; ++a) {
    const std::size_t e = k - 1 - a;
    const double l = std::max(lambda[e], 0.0);
    out.variances[a] = l;
    kept += l;
    for (std::size_t t = 0; t < k; ++t) axis[t * dims + a] = g[t * k + e] * std::sqrt(l);
  }
#pragma omp parallel for schedule(static) if (parallel)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(n); ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    for (std::size_t a = 0; a < dims; ++a) {
      double s = 0.0;
      for (std::size_t t = 0; t < k; ++t) s += q[t * n + iu] * axis[t * dims + a];
      out.coords[iu * dims + a] = static_cast<float>(s);
    }
  }

  // Centred energy of M: sum of squares minus n * |mean row|^2.
  const double nd = static_cast<double>(n);
  double mean_sq = 0.0;
  for (const double s : col_sum) mean_sq += (s / nd) * (s / nd);
  if (cols)
    for (const double s : row_sum) mean_sq += (s / nd) * (s / nd);
  const double total = (cols ? 2.0 : 1.0) * sum_sq - nd * mean_sq;
  out.captured = total > 0.0 ? std::min(1.0, kept / total) : 1.0;
  return out;
}

}  // namespace bounce
