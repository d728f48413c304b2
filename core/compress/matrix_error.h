#pragma once
// Errors of a decompressed matrix against the exact one: the three figures
// of the published compression method (mean, max and sum of |error| over all entries) and the
// relative Frobenius error. Channels are added one after another.
#include <cstddef>

namespace bounce {

struct MatrixError {
  double mean_abs = 0.0;
  double max_abs = 0.0;
  double sum_abs = 0.0;
  double rel_frobenius = 0.0;  // ||approx - exact||_F / ||exact||_F
  std::size_t entries = 0;
};

class MatrixErrorAccumulator {
 public:
  void add(const float* exact, const float* approx, std::size_t count);
  MatrixError result() const;

 private:
  double sum_abs_ = 0.0, max_abs_ = 0.0, diff2_ = 0.0, exact2_ = 0.0;
  std::size_t count_ = 0;
};

}  // namespace bounce
