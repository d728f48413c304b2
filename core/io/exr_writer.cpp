#include "io/exr_writer.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <atomic>
#include <string>
#include <system_error>

#include <unistd.h>

#include "io/atomic_file.h"

namespace bounce {

namespace fs = std::filesystem;

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "pixels are handed to OIIO as packed RGB");

void write_exr(const fs::path& path, const RgbFloatImage& image) {
  static std::atomic<unsigned> counter{0};
  // OIIO picks the format from the extension: keep ".exr" at the end.
  const fs::path temp =
      path.parent_path() / ("." + path.stem().string() + ".tmp-" + std::to_string(::getpid()) +
                            "-" + std::to_string(counter++) + ".exr");
  auto out = OIIO::ImageOutput::create(temp.string());
  if (!out) throw IoError(path.string(), "cannot write EXR: " + OIIO::geterror());
  OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");  // lossless
  const bool ok = out->open(temp.string(), spec) &&
                  out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()) && out->close();
  if (!ok) {
    const std::string why = out->geterror();
    std::error_code ec;
    fs::remove(temp, ec);
    throw IoError(path.string(), "cannot write EXR: " + why);
  }
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw IoError(path.string(), "cannot move into place: " + ec.message());
  }
}

RgbFloatImage read_exr(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) throw IoError(path.string(), "cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  const auto nch = static_cast<std::size_t>(spec.nchannels);
  RgbFloatImage image(spec.width, spec.height);
  std::vector<float> all(image.pixels.size() * nch);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()))
    throw IoError(path.string(), "cannot read image: " + in->geterror());
  for (std::size_t p = 0; p < image.pixels.size(); ++p)
    for (std::size_t c = 0; c < 3; ++c)
      image.pixels[p][static_cast<int>(c)] = all[p * nch + std::min(c, nch - 1)];
  return image;
}

}  // namespace bounce
