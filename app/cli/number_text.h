#pragma once
// Numbers in the CLI's tables: fixed point with a given number of digits.
#include <cstdio>
#include <string>

namespace bounce::cli {

inline std::string fixed(double v, int digits) {
  char s[64];
  std::snprintf(s, sizeof s, "%.*f", digits, v);
  return s;
}

}  // namespace bounce::cli
