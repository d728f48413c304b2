#pragma once
// A load's warnings as text, one "where: message" line each, for the
// message of a failed expectation.
#include <string>

#include "base/diagnostics.h"

namespace bounce::test {

inline std::string warnings_of(const Diagnostics& d) {
  std::string text;
  for (const Diagnostic& w : d.warnings()) text += w.where + ": " + w.message + "\n";
  return text;
}

}  // namespace bounce::test
