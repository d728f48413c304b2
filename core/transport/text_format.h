#pragma once
// printf-style formatting into a std::string for decision and warning texts
// (GCC 12's libstdc++ has no std::format).
#include <cstdio>
#include <string>

namespace bounce {

template <class... Args>
std::string text_format(const char* fmt, Args... args) {
  const int size = std::snprintf(nullptr, 0, fmt, args...);
  if (size <= 0) return {};
  std::string s(static_cast<std::size_t>(size) + 1, '\0');
  std::snprintf(s.data(), s.size(), fmt, args...);
  s.pop_back();
  return s;
}

}  // namespace bounce
