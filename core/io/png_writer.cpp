#include "io/png_writer.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <string>

#include "io/atomic_file.h"
#include "io/image_file.h"

namespace bounce {

namespace fs = std::filesystem;

void write_png(const fs::path& path, const Rgb8Image& image) {
  write_image_atomically(path, OIIO::ImageSpec(image.width, image.height, 3, OIIO::TypeDesc::UINT8),
                         image.pixels.data(), "PNG");
}

Rgb8Image read_png(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) throw IoError(path.string(), "cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  Rgb8Image image(spec.width, spec.height);
  std::vector<std::uint8_t> all(
      static_cast<std::size_t>(spec.width * spec.height * spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, all.data()))
    throw IoError(path.string(), "cannot read image: " + in->geterror());
  for (std::size_t p = 0; p < static_cast<std::size_t>(spec.width * spec.height); ++p)
    for (int c = 0; c < 3; ++c)
      image.pixels[p * 3 + static_cast<std::size_t>(c)] =
          all[p * static_cast<std::size_t>(spec.nchannels) +
              static_cast<std::size_t>(std::min(c, spec.nchannels - 1))];
  return image;
}

}  // namespace bounce
