#pragma once
// A picture of where an approximate image differs from an exact one: each
// pixel the camera saw coloured by its relative error |x - y| / max(|y|,
// floor) (Euclidean over R, G, B; the floor, 5% of the mean |y| over seen
// pixels, keeps nearly unlit pixels from dominating) on the perceptual colour
// map, from 0 to `full_scale` (clipped above); background black.
#include <vector>

#include "io/exr_writer.h"
#include "io/png_writer.h"

namespace bounce {

// |x - y| per pixel and channel (linear), for an EXR of the error itself.
RgbFloatImage absolute_difference(const RgbFloatImage& test, const RgbFloatImage& reference);

// Throws bounce::Error when the sizes differ or full_scale <= 0.
Rgb8Image relative_error_heat_map(const RgbFloatImage& test, const RgbFloatImage& reference,
                                  const std::vector<float>& coverage, double full_scale);

}  // namespace bounce
