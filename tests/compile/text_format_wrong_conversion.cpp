// Must not compile: text_format checks its conversions like printf does
// (tests/CMakeLists.txt compiles this file and expects the format error).
#include "transport/text_format.h"

std::string wrong() { return bounce::text_format("%d patches", 2.5); }
