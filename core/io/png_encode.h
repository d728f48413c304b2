#pragma once
// Encoding 8-bit pixels as PNG bytes in memory (via OpenImageIO), for files
// that embed images instead of writing them beside themselves (binary glTF).
#include <cstdint>
#include <string>
#include <vector>

namespace bounce {

// `pixels`: width x height x channels bytes (1 grey, 2 grey + alpha, 3 RGB,
// 4 RGBA), row-major, top row first. `what` names the image in errors.
// Throws bounce::Error when the sizes do not fit or the encoder fails.
std::vector<std::uint8_t> encode_png(int width, int height, int channels,
                                     const std::vector<std::uint8_t>& pixels,
                                     const std::string& what);

}  // namespace bounce
