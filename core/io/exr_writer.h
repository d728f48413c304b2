#pragma once
// Linear RGB float pictures as OpenEXR (via OpenImageIO), written to a
// temporary name and renamed, like io/png_writer.h: the exact values a
// renderer computed, for comparisons that 8-bit PNGs cannot carry.
#include <cstddef>
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

struct RgbFloatImage {
  int width = 0, height = 0;
  std::vector<glm::vec3> pixels;  // width * height, row-major, top row first
  RgbFloatImage() = default;
  RgbFloatImage(int w, int h)
      : width(w), height(h), pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h)) {}
  glm::vec3& at(int x, int y) { return pixels[index(x, y)]; }
  const glm::vec3& at(int x, int y) const { return pixels[index(x, y)]; }
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
           static_cast<std::size_t>(x);
  }
};

// 32-bit float channels R, G, B (half would round radiance to 3 digits).
void write_exr(const std::filesystem::path& path, const RgbFloatImage& image);
RgbFloatImage read_exr(const std::filesystem::path& path);

}  // namespace bounce
