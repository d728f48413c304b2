#include "io/exr_writer.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <string>

#include "io/atomic_file.h"
#include "io/image_file.h"

namespace bounce {

namespace fs = std::filesystem;

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "pixels are handed to OIIO as packed RGB");

void write_exr(const fs::path& path, const RgbFloatImage& image) {
  OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");  // lossless
  write_image_atomically(path, spec, image.pixels.data(), "EXR");
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
