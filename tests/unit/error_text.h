#pragma once
// The message of the error a reader throws, for tests that check what a bad
// file is refused with.
#include <string>

namespace bounce::test {

// What the `E` thrown by `read()` says, or "" when `read()` returns.
template <typename E, typename Read>
std::string error_text(Read&& read) {
  try {
    read();
    return "";
  } catch (const E& e) {
    return e.what();
  }
}

}  // namespace bounce::test
