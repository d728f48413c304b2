#pragma once
// Pictures of matrices for people: the transport matrix with a logarithmic
// colour map (before and after reordering), and compression error heatmaps
// per element and per 4x4 block. The studio shows the same pictures.
//
// Layout: the matrix (downsampled by block maxima to at most `max_size`
// pixels a side, so isolated large entries stay visible), a gap, and a
// vertical colour bar whose ticks mark each decade below the maximum, each
// labelled with its value, and an optional caption above.
#include <cstdint>
#include <string>
#include <vector>

#include "io/png_writer.h"

namespace bounce {

struct MatrixPictureSettings {
  int max_size = 1024;   // pixels along a side of the matrix area
  double decades = 6.0;  // colour range: [max / 10^decades, max]
  std::string title;     // caption above the matrix (none if empty)
};

// Viridis-like perceptual colour map, t in [0, 1].
void colormap(double t, std::uint8_t rgb[3]);

// |values| of an n x n row-major matrix, log colour scale; exact zeros black.
// If `permutation` is given, shows M[perm[i]][perm[j]].
Rgb8Image matrix_picture(const float* values, std::size_t n, const MatrixPictureSettings& settings,
                         const std::vector<std::uint32_t>* permutation = nullptr);

// Sum of |error| over each 4x4 block of an n x n error matrix, as a
// (n/4 x n/4) matrix (n rounded up), to be drawn with matrix_picture.
std::vector<float> block_error_sums(const float* abs_error, std::size_t n, std::size_t& blocks);

}  // namespace bounce
