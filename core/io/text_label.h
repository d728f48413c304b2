#pragma once
// Text on pictures (colour-bar values, captions), drawn with OpenImageIO's
// FreeType text renderer in DejaVu Sans (Debian package fonts-dejavu-core,
// installed by dev.sh).
#include <string>

#include "io/png_writer.h"

namespace bounce {

// Width in pixels of `text` at `size` pixels, as drawn by draw_text.
int text_width(const std::string& text, int size);

// Draws `text` in black with its baseline-left corner at (x, y). Returns
// false (and draws nothing) when the font cannot be found or loaded: labels
// are a reading aid, the picture stays correct without them.
bool draw_text(Rgb8Image& image, int x, int y, const std::string& text, int size);

}  // namespace bounce
