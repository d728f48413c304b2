#include "io/png_writer.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <atomic>
#include <string>
#include <system_error>

#include <unistd.h>

#include "io/atomic_file.h"

namespace bounce {

namespace fs = std::filesystem;

void write_png(const fs::path& path, const Rgb8Image& image) {
  static std::atomic<unsigned> counter{0};
  // OIIO picks the format from the extension: keep ".png" at the end.
  const fs::path temp =
      path.parent_path() / ("." + path.stem().string() + ".tmp-" + std::to_string(::getpid()) +
                            "-" + std::to_string(counter++) + ".png");
  auto out = OIIO::ImageOutput::create(temp.string());
  if (!out) throw IoError(path.string(), "cannot write PNG: " + OIIO::geterror());
  const OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
  const bool ok = out->open(temp.string(), spec) &&
                  out->write_image(OIIO::TypeDesc::UINT8, image.pixels.data()) && out->close();
  if (!ok) {
    const std::string why = out->geterror();
    std::error_code ec;
    fs::remove(temp, ec);
    throw IoError(path.string(), "cannot write PNG: " + why);
  }
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) throw IoError(path.string(), "cannot move into place: " + ec.message());
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
