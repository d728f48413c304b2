#pragma once
// BLAS and LAPACK take 32-bit dimensions here (OpenBLAS's blasint and
// LAPACKE's lapack_int are int on Debian's LP64 builds): convert once, with a
// clear error instead of a silent wrap-around.
#include <cstddef>
#include <limits>
#include <string>

#include "base/error.h"

namespace bounce {

inline int blas_dim(std::size_t value, const char* routine) {
  if (value > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw Error("transport", std::string(routine) + ": dimension " + std::to_string(value) +
                                 " exceeds the 32-bit BLAS/LAPACK interface");
  return static_cast<int>(value);
}

}  // namespace bounce
