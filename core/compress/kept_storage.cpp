#include "compress/kept_storage.h"

// The conversions are Imath's (OpenEXR's half), without its 256 KiB lookup
// table, so nothing here needs the Imath library at link time.
#define IMATH_HALF_NO_LOOKUP_TABLE
#include <Imath/half.h>

#include <cmath>
#include <limits>

#include "base/error.h"

namespace bounce {

namespace {
constexpr float kHalfMax = 65504.0f;
}  // namespace

const char* kept_storage_name(KeptStorage storage) {
  return storage == KeptStorage::kFloat16 ? "float16" : "float32";
}

std::optional<KeptStorage> parse_kept_storage(const std::string& name) {
  if (name == "float32") return KeptStorage::kFloat32;
  if (name == "float16") return KeptStorage::kFloat16;
  return std::nullopt;
}

bool kept_columns_are_short(KeptStorage storage, std::size_t n) {
  return storage == KeptStorage::kFloat16 &&
         n <= static_cast<std::size_t>(std::numeric_limits<std::uint16_t>::max()) + 1;
}

std::size_t kept_entry_bytes(KeptStorage storage, std::size_t n) {
  const std::size_t column = kept_columns_are_short(storage, n) ? 2 : 4;
  return column + (storage == KeptStorage::kFloat16 ? 2 : 4);
}

bool fits_half(std::span<const float> values) {
  for (const float v : values)
    if (!std::isfinite(v) || std::abs(v) > kHalfMax) return false;
  return true;
}

void round_to_half(std::span<float> values) {
  for (float& v : values) v = imath_half_to_float(imath_float_to_half(v));
}

void to_half_bits(std::span<const float> values, std::span<std::uint16_t> bits) {
  if (bits.size() != values.size()) throw Error("half", "one half per value expected");
  for (std::size_t k = 0; k < values.size(); ++k) bits[k] = imath_float_to_half(values[k]);
}

void from_half_bits(std::span<const std::uint16_t> bits, std::span<float> values) {
  if (bits.size() != values.size()) throw Error("half", "one value per half expected");
  for (std::size_t k = 0; k < bits.size(); ++k) values[k] = imath_half_to_float(bits[k]);
}

}  // namespace bounce
