#pragma once
// Sizes computed from numbers read out of files (array shapes, image sizes,
// counts in a manifest). A hostile file can make such a product wrap around
// 64 bits to something small that passes a size check, and then ask for a
// huge allocation; every such product goes through these instead of `*`.
#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>

#include "base/error.h"

namespace bounce {

// a * b, or nothing when it does not fit in std::size_t.
inline std::optional<std::size_t> checked_product(std::size_t a, std::size_t b) {
  std::size_t p = 0;
  if (__builtin_mul_overflow(a, b, &p)) return std::nullopt;
  return p;
}

// The product of all `factors` (1 for none), or nothing when it overflows.
inline std::optional<std::size_t> checked_product(std::span<const std::size_t> factors) {
  std::size_t p = 1;
  for (std::size_t f : factors) {
    const auto next = checked_product(p, f);
    if (!next) return std::nullopt;
    p = *next;
  }
  return p;
}

inline std::optional<std::size_t> checked_product(std::initializer_list<std::size_t> factors) {
  return checked_product(std::span<const std::size_t>(factors.begin(), factors.size()));
}

// The size in bytes of the regular file `path`. Anything else (a folder, a
// device such as /dev/zero, a FIFO that would block the reader) is refused
// with an `E` (an Error subclass) naming it, so that readers can compare
// what a header asks for with what the file holds before they allocate.
template <typename E = Error>
std::size_t regular_file_size(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status))
    throw E(path.string(),
            "cannot open file: " + (ec ? ec.message() : std::string("No such file or directory")));
  if (!std::filesystem::is_regular_file(status))
    throw E(path.string(), "cannot open file: not a regular file");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw E(path.string(), "cannot open file: " + ec.message());
  return static_cast<std::size_t>(size);
}

}  // namespace bounce
