#include "transport/text_format.h"

#include <cstdarg>
#include <cstdio>

namespace bounce {

std::string text_format(const char* fmt, ...) {
  std::va_list args;
  va_start(args, fmt);
  std::va_list again;
  va_copy(again, args);
  const int size = std::vsnprintf(nullptr, 0, fmt, args);
  va_end(args);
  std::string s;
  if (size > 0) {
    s.resize(static_cast<std::size_t>(size) + 1);
    std::vsnprintf(s.data(), s.size(), fmt, again);
    s.pop_back();
  }
  va_end(again);
  return s;
}

}  // namespace bounce
