#include "formfactor/balance.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"

namespace bounce {

namespace {

// (S x)_p for the symmetric S stored row-major in `s`, each row summed in
// float64 in column order.
void multiply(const float* s, std::size_t n, const std::vector<double>& x,
              std::vector<double>& out) {
#pragma omp parallel for schedule(static)
  for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(n); ++pi) {
    const float* row = s + static_cast<std::size_t>(pi) * n;
    double sum = 0.0;
    for (std::size_t q = 0; q < n; ++q) sum += static_cast<double>(row[q]) * x[q];
    out[static_cast<std::size_t>(pi)] = sum;
  }
}

}  // namespace

BalanceStats balance_form_factors(FormFactorMatrix& f, const std::vector<float>& area,
                                  const std::vector<float>& closure,
                                  const BalanceSettings& settings, Progress* progress) {
  const std::size_t n = f.n;
  if (area.size() != n || closure.size() != n || f.values.size() != n * n)
    throw Error("form factors", "balancing: sizes of F, areas and closures differ");
  BalanceStats stats;
  stats.row_scale.assign(n, 1.0f);
  if (n == 0) {
    stats.converged = true;
    return stats;
  }
  float* values = f.values.data();

  // Raw row sums, then S = (diag(A) F + (diag(A) F)^T) / 2 in place.
  std::vector<double> raw_row(n, 0.0);
#pragma omp parallel for schedule(static)
  for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(n); ++pi) {
    const float* row = values + static_cast<std::size_t>(pi) * n;
    double sum = 0.0;
    for (std::size_t q = 0; q < n; ++q) sum += row[q];
    raw_row[static_cast<std::size_t>(pi)] = sum;
  }
#pragma omp parallel for schedule(dynamic, 16)
  for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(n); ++pi) {
    const auto p = static_cast<std::size_t>(pi);
    const double ap = area[p];
    for (std::size_t q = p; q < n; ++q) {
      const double s =
          0.5 * (ap * values[p * n + q] + static_cast<double>(area[q]) * values[q * n + p]);
      values[p * n + q] = static_cast<float>(s);
      values[q * n + p] = static_cast<float>(s);
    }
  }

  std::vector<double> target(n);
  for (std::size_t p = 0; p < n; ++p) {
    double c = closure[p];
    if (!(c > 0.0) && raw_row[p] > 0.0) {
      c = std::min(1.0, raw_row[p]);
      ++stats.kept_raw_targets;
      stats.raw_target_patches.push_back(p);
    }
    // A closure far from the raw row means the quadrature failed for this
    // patch (its visibility rays blocked, a crevice): its row says little
    // about where its light goes, and forcing it to the closure would scale
    // it (and its column) by orders of magnitude. Trust the closure within
    // a factor. (Scaling down is always safe: rows never exceed closures.)
    if (c > raw_row[p] * settings.max_row_scale) {
      c = raw_row[p] * settings.max_row_scale;
      ++stats.limited_targets;
    }
    target[p] = static_cast<double>(area[p]) * c;
  }

  std::vector<double> x(n, 1.0), sx(n, 0.0);
  const auto residual = [&] {
    double worst = 0.0;
    for (std::size_t p = 0; p < n; ++p) {
      if (target[p] > 0.0)
        worst = std::max(worst, std::abs(x[p] * sx[p] - target[p]) / target[p]);
      else
        worst = std::max(worst, x[p] * sx[p] > 0.0 ? 1.0 : 0.0);
    }
    return worst;
  };
  if (progress) progress->begin_stage("balance form factors", 1);
  multiply(values, n, x, sx);
  stats.residual = residual();
  // Stagnation: targets no symmetric scaling can meet (two surfaces that see
  // only each other must exchange equal energy, so their closures' noise
  // makes them inconsistent) leave a residual that stops falling.
  double best = stats.residual;
  int best_at = 0;
  while (stats.residual > settings.tolerance && stats.iterations < settings.max_iterations &&
         stats.iterations - best_at < settings.stagnation_iterations) {
    if (progress) progress->check();
    for (std::size_t p = 0; p < n; ++p)
      x[p] = sx[p] > 0.0 && target[p] > 0.0 ? std::sqrt(x[p] * target[p] / sx[p]) : 0.0;
    multiply(values, n, x, sx);
    stats.residual = residual();
    ++stats.iterations;
    if (stats.residual < 0.99 * best) {
      best = stats.residual;
      best_at = stats.iterations;
    }
  }
  stats.converged = stats.residual <= settings.tolerance;
  if (!stats.converged) {
    // No row may end above its closure: one more symmetric scaling by
    // y_p = min(1, t_p / row_p) brings every row to at most its target
    // (row_p y_p sum_q S_pq x_q y_q <= y_p row_p) and keeps reciprocity.
    for (std::size_t p = 0; p < n; ++p) {
      const double row = x[p] * sx[p];
      if (row > target[p] && row > 0.0) x[p] *= target[p] / row;
    }
    multiply(values, n, x, sx);
    stats.residual = residual();
  }

  // F'_pq = x_p S_pq x_q / A_p; each entry from the S entry in its own place.
#pragma omp parallel for schedule(static)
  for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(n); ++pi) {
    const auto p = static_cast<std::size_t>(pi);
    float* row = values + p * n;
    const double scale = area[p] > 0.0f ? x[p] / static_cast<double>(area[p]) : 0.0;
    for (std::size_t q = 0; q < n; ++q)
      row[q] = static_cast<float>(scale * static_cast<double>(row[q]) * x[q]);
  }
  stats.row_scale_min = stats.row_scale_max = 1.0;
  bool first = true;
  for (std::size_t p = 0; p < n; ++p) {
    if (!(raw_row[p] > 0.0)) continue;
    const double balanced = x[p] * sx[p] / static_cast<double>(area[p]);
    const double scale = balanced / raw_row[p];
    stats.row_scale[p] = static_cast<float>(scale);
    stats.row_scale_min = first ? scale : std::min(stats.row_scale_min, scale);
    stats.row_scale_max = first ? scale : std::max(stats.row_scale_max, scale);
    first = false;
  }
  if (progress) {
    progress->advance();
    progress->end_stage();
  }
  f.area = area;  // A F is symmetric now: the transport may use Cholesky
  return stats;
}

}  // namespace bounce
