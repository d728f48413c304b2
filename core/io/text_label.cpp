#include "io/text_label.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <filesystem>

namespace bounce {

namespace {

const std::string& font_path() {
  static const std::string path = [] {
    for (const char* p :
         {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/TTF/DejaVuSans.ttf"})
      if (std::filesystem::exists(p)) return std::string(p);
    return std::string();
  }();
  return path;
}

}  // namespace

int text_width(const std::string& text, int size) {
  if (font_path().empty() || text.empty()) return 0;
  const OIIO::ROI roi = OIIO::ImageBufAlgo::text_size(text, size, font_path());
  return roi.defined() ? roi.width() : 0;
}

bool draw_text(Rgb8Image& image, int x, int y, const std::string& text, int size) {
  if (font_path().empty()) return false;
  // Wraps the pixels without copying; OIIO blends the glyphs into them.
  OIIO::ImageBuf buf(OIIO::ImageSpec(image.width, image.height, 3, OIIO::TypeDesc::UINT8),
                     image.pixels.data());
  const float black[3] = {0.0f, 0.0f, 0.0f};
  return OIIO::ImageBufAlgo::render_text(buf, x, y, text, size, font_path(), black);
}

}  // namespace bounce
