#pragma once
// Public: 8-bit pictures of linear light.
//
//   const float exposure = bounce::ToneMap::exposure_for(linear_colours);
//   image.pixels[i] = bounce::ToneMap::srgb8(exposure * linear);  // per channel
//   bounce::draw_text(image, x, y, "0.25", 12);
//   bounce::write_png(path, image);
//
// One tone map for every 8-bit output (the 99th percentile of luminance to
// 0.9, then the sRGB curve), so the library's PNGs, PLY colours and a front
// end's own pictures agree; labels drawn in DejaVu Sans (draw_text returns
// false and draws nothing when the font is missing).
#include "io/png_writer.h"
#include "io/text_label.h"
#include "io/tone_map.h"
