#include "io/png_encode.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "base/error.h"

namespace bounce {

std::vector<std::uint8_t> encode_png(int width, int height, int channels,
                                     const std::vector<std::uint8_t>& pixels,
                                     const std::string& what) {
  if (width < 1 || height < 1 || channels < 1 || channels > 4 ||
      pixels.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                           static_cast<std::size_t>(channels))
    throw Error(what, "PNG: the pixels do not fit the image's size");
  std::vector<std::uint8_t> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  // The name only picks the format: the bytes go to `proxy`.
  auto out = OIIO::ImageOutput::create("embedded.png", &proxy);
  if (!out || !out->supports("ioproxy"))
    throw Error(what, "PNG: this OpenImageIO cannot encode PNG in memory: " + OIIO::geterror());
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  if (channels == 2 || channels == 4) spec.alpha_channel = channels - 1;
  // The bytes are already what the file must hold (sRGB colour, linear
  // alpha): no premultiplication or conversion on the way.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  if (!out->open("embedded.png", spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) ||
      !out->close())
    throw Error(what, "PNG: cannot encode: " + out->geterror());
  return bytes;
}

}  // namespace bounce
