#pragma once
// PNG pictures (via OpenImageIO), written to a temporary name and renamed so
// a reader never sees half a picture.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace bounce {

struct Rgb8Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 3, row-major, top row first
  Rgb8Image() = default;
  Rgb8Image(int w, int h) : width(w), height(h), pixels(static_cast<std::size_t>(w * h) * 3, 0) {}
  std::uint8_t* at(int x, int y) {
    return &pixels[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                    static_cast<std::size_t>(x)) *
                   3];
  }
};

void write_png(const std::filesystem::path& path, const Rgb8Image& image);
Rgb8Image read_png(const std::filesystem::path& path);

}  // namespace bounce
