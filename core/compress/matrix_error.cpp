#include "compress/matrix_error.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace bounce {

void MatrixErrorAccumulator::add(const float* exact, const float* approx, std::size_t count) {
  double sum = 0.0, mx = 0.0, d2 = 0.0, e2 = 0.0;
#pragma omp parallel for reduction(+ : sum, d2, e2) reduction(max : mx) schedule(static)
  for (std::int64_t k = 0; k < static_cast<std::int64_t>(count); ++k) {
    const double e = exact[k], d = static_cast<double>(approx[k]) - e;
    sum += std::abs(d);
    mx = std::max(mx, std::abs(d));
    d2 += d * d;
    e2 += e * e;
  }
  sum_abs_ += sum;
  max_abs_ = std::max(max_abs_, mx);
  diff2_ += d2;
  exact2_ += e2;
  count_ += count;
}

MatrixError MatrixErrorAccumulator::result() const {
  MatrixError e;
  e.entries = count_;
  e.sum_abs = sum_abs_;
  e.max_abs = max_abs_;
  e.mean_abs = count_ ? sum_abs_ / static_cast<double>(count_) : 0.0;
  e.rel_frobenius = exact2_ > 0.0 ? std::sqrt(diff2_ / exact2_) : 0.0;
  return e;
}

}  // namespace bounce
