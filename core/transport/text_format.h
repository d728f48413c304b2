#pragma once
// printf-style formatting into a std::string for decision and warning texts
// (GCC 12's libstdc++ has no std::format). A C variadic function with the
// printf format attribute, not a template over snprintf: the compiler then
// checks every call's conversions against its arguments (-Wformat), and the
// build makes a mismatch an error (-Werror=format in bounce_warnings).
#include <string>

namespace bounce {

std::string text_format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

}  // namespace bounce
