#include "compress/matrix_picture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/text_label.h"

namespace bounce {

void colormap(double t, std::uint8_t rgb[3]) {
  // Viridis at nine stops, linearly interpolated.
  static constexpr std::uint8_t kStops[9][3] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},
                                                {44, 113, 142}, {33, 144, 141}, {39, 173, 129},
                                                {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};
  t = std::clamp(t, 0.0, 1.0) * 8.0;
  const int k = std::min(7, static_cast<int>(t));
  const double f = t - k;
  for (int c = 0; c < 3; ++c)
    rgb[c] =
        static_cast<std::uint8_t>(std::lround((1.0 - f) * kStops[k][c] + f * kStops[k + 1][c]));
}

Rgb8Image matrix_picture(const float* values, std::size_t n, const MatrixPictureSettings& s,
                         const std::vector<std::uint32_t>* perm) {
  const int size = static_cast<int>(std::min<std::size_t>(n, static_cast<std::size_t>(s.max_size)));
  const int bar_gap = std::max(8, size / 32), bar_width = std::max(12, size / 24);
  const int margin = std::max(4, size / 64);
  // Labels: one decade value per tick right of the bar, the caption on top.
  const int font = std::max(10, size / 48);
  const int label_width = text_width("0.0e-00", font) + (text_width("0", font) > 0 ? font / 2 : 0);
  const int top = s.title.empty() || text_width(s.title, font) == 0 ? margin : margin + 2 * font;
  Rgb8Image img(size + bar_gap + bar_width + label_width + 2 * margin, size + top + margin);
  std::fill(img.pixels.begin(), img.pixels.end(), std::uint8_t{255});  // white background

  // Block maxima of |value| per pixel.
  std::vector<float> pix(static_cast<std::size_t>(size) * static_cast<std::size_t>(size), 0.0f);
  float vmax = 0.0f;
#pragma omp parallel for reduction(max : vmax) schedule(static)
  for (int y = 0; y < size; ++y) {
    const std::size_t i0 = static_cast<std::size_t>(y) * n / static_cast<std::size_t>(size);
    const std::size_t i1 =
        std::max(i0 + 1, static_cast<std::size_t>(y + 1) * n / static_cast<std::size_t>(size));
    for (std::size_t i = i0; i < i1; ++i) {
      const std::size_t row = perm ? (*perm)[i] : i;
      for (int x = 0; x < size; ++x) {
        const std::size_t j0 = static_cast<std::size_t>(x) * n / static_cast<std::size_t>(size);
        const std::size_t j1 =
            std::max(j0 + 1, static_cast<std::size_t>(x + 1) * n / static_cast<std::size_t>(size));
        float m = pix[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) +
                      static_cast<std::size_t>(x)];
        for (std::size_t j = j0; j < j1; ++j) {
          const std::size_t col = perm ? (*perm)[j] : j;
          m = std::max(m, std::abs(values[row * n + col]));
        }
        pix[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) +
            static_cast<std::size_t>(x)] = m;
        vmax = std::max(vmax, m);
      }
    }
  }
  const double log_max = vmax > 0.0f ? std::log10(static_cast<double>(vmax)) : 0.0;
  const double bottom = log_max - s.decades;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float m = pix[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) +
                          static_cast<std::size_t>(x)];
      std::uint8_t* px = img.at(margin + x, top + y);
      if (!(m > 0.0f)) {
        px[0] = px[1] = px[2] = 0;
        continue;
      }
      colormap((std::log10(static_cast<double>(m)) - bottom) / s.decades, px);
    }
  // Colour bar, top = max; a dark tick across it at every decade.
  const int bx = margin + size + bar_gap;
  for (int y = 0; y < size; ++y) {
    const double t = 1.0 - (y + 0.5) / size;
    std::uint8_t c[3];
    colormap(t, c);
    const bool tick = static_cast<int>(std::floor(t * s.decades)) !=
                      static_cast<int>(std::floor((1.0 - (y + 1.5) / size) * s.decades));
    for (int x = 0; x < bar_width; ++x) {
      std::uint8_t* px = img.at(bx + x, top + y);
      for (int k = 0; k < 3; ++k) px[k] = tick ? 255 : c[k];
    }
  }
  if (label_width > 0 && vmax > 0.0f) {
    // The value at the top of the bar and at each decade below it.
    for (int k = 0; k <= static_cast<int>(s.decades); ++k) {
      const int y = top + static_cast<int>(std::lround(k / s.decades * size));
      char label[32];
      std::snprintf(label, sizeof label, "%.1e", std::pow(10.0, log_max - k));
      draw_text(img, bx + bar_width + font / 3, std::min(y + font / 3, top + size), label, font);
    }
  }
  if (top > margin) draw_text(img, margin, top - font / 2, s.title, font);
  return img;
}

std::vector<float> block_error_sums(const float* abs_error, std::size_t n, std::size_t& blocks) {
  blocks = (n + 3) / 4;
  std::vector<float> sums(blocks * blocks, 0.0f);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      sums[(i / 4) * blocks + j / 4] += std::abs(abs_error[i * n + j]);
  return sums;
}

}  // namespace bounce
