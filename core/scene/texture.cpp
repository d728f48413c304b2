#include "scene/texture.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <initializer_list>
#include <system_error>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace bounce {

namespace {

namespace fs = std::filesystem;

// Texel (x, y) of a level, wrapping both ways.
const glm::vec3& texel(const Texture::Level& l, int x, int y) {
  x %= l.width;
  y %= l.height;
  if (x < 0) x += l.width;
  if (y < 0) y += l.height;
  return l.texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(l.width) +
                  static_cast<std::size_t>(x)];
}

// Each texel the mean of the (up to) 2x2 texels it covers.
Texture::Level half(const Texture::Level& in) {
  Texture::Level out;
  out.width = std::max(1, in.width / 2);
  out.height = std::max(1, in.height / 2);
  out.texels.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height));
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const int x0 = std::min(2 * x, in.width - 1), x1 = std::min(2 * x + 1, in.width - 1);
      const int y0 = std::min(2 * y, in.height - 1), y1 = std::min(2 * y + 1, in.height - 1);
      out.texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(out.width) +
                 static_cast<std::size_t>(x)] =
          0.25f * (texel(in, x0, y0) + texel(in, x1, y0) + texel(in, x0, y1) + texel(in, x1, y1));
    }
  return out;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// The extension naming an embedded image's format: the mesh file's hint,
// else what the bytes start with (glTF states a MIME type, which Assimp
// turns into the hint, but other formats may not).
std::string embedded_extension(const EmbeddedImage& image) {
  const std::string& hint = image.format_hint;
  if (!hint.empty() &&
      std::all_of(hint.begin(), hint.end(), [](unsigned char c) { return std::isalnum(c) != 0; }))
    return lower(hint);
  const auto starts = [&](std::initializer_list<std::uint8_t> magic) {
    return image.bytes.size() >= magic.size() &&
           std::equal(magic.begin(), magic.end(), image.bytes.begin());
  };
  if (starts({0x89, 'P', 'N', 'G'})) return "png";
  if (starts({0xff, 0xd8, 0xff})) return "jpg";
  return "png";  // a guess: OpenImageIO tries its other readers when it is wrong
}

// OpenImageIO's error text on one line: its readers report one line per
// library layer ("PNG read error: ...\nPNG library error"), and a warning
// is one line.
std::string one_line(std::string text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at))
    text.replace(at, 1, "; ");
  return text;
}

// Raw embedded RGBA8 texels as a PNG of them would read: 8-bit, sRGB, alpha
// last; the colour as stored, not multiplied by alpha.
std::optional<ImagePixels> raw_pixels(const EmbeddedImage& image, std::string& error) {
  const auto texels =
      static_cast<std::size_t>(image.raw_width) * static_cast<std::size_t>(image.raw_height);
  if (image.raw_height <= 0 || image.bytes.size() != texels * 4) {
    error = "the embedded image's texels do not fill " + std::to_string(image.raw_width) + " x " +
            std::to_string(image.raw_height);
    return std::nullopt;
  }
  ImagePixels out;
  out.width = image.raw_width;
  out.height = image.raw_height;
  out.channels = 4;
  out.alpha_channel = 3;
  out.srgb = true;
  out.pixels.reserve(image.bytes.size());
  for (const std::uint8_t b : image.bytes) out.pixels.push_back(static_cast<float>(b) / 255.0f);
  return out;
}

// Whether OpenImageIO's reader for this format hands over colour multiplied
// by alpha unless it says otherwise (oiio:UnassociatedAlpha): OpenEXR
// stores it so, and a TIFF or TGA file may; the readers that honour the
// hint say so when they do. Other readers (BMP, DDS, ...) never multiply.
bool stores_associated_alpha(const char* format) {
  const std::string f = format;
  return f == "openexr" || f == "tiff" || f == "targa" || f == "png" || f == "psd" ||
         f == "jpeg2000" || f == "webp";
}

// Divides the colour channels by alpha where it is above 0 (where it is 0
// the colour is lost, and stays 0).
void unassociate(ImagePixels& image) {
  const auto channels = static_cast<std::size_t>(image.channels);
  const auto alpha = static_cast<std::size_t>(image.alpha_channel);
  for (std::size_t p = 0; p < image.pixels.size(); p += channels) {
    const float a = image.pixels[p + alpha];
    if (!(a > 0.0f) || a >= 1.0f) continue;
    for (std::size_t c = 0; c < std::min<std::size_t>(channels, 3); ++c)
      if (c != alpha) image.pixels[p + c] /= a;
  }
}

}  // namespace

float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

glm::vec3 Texture::lookup(glm::vec2 uv, int level) const {
  const Level& l =
      levels[static_cast<std::size_t>(std::clamp(level, 0, static_cast<int>(levels.size()) - 1))];
  // Texel centres at half-integers; v up, row 0 at the top.
  const float x = uv.x * static_cast<float>(l.width) - 0.5f;
  const float y = (1.0f - uv.y) * static_cast<float>(l.height) - 0.5f;
  if (!std::isfinite(x) || !std::isfinite(y)) return mean;
  // Wrap far coordinates first so the int conversion cannot overflow.
  const float xw = x - static_cast<float>(l.width) * std::floor(x / static_cast<float>(l.width));
  const float yw = y - static_cast<float>(l.height) * std::floor(y / static_cast<float>(l.height));
  const float fx = std::floor(xw), fy = std::floor(yw);
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  const float ax = xw - fx, ay = yw - fy;
  return (1.0f - ay) * ((1.0f - ax) * texel(l, x0, y0) + ax * texel(l, x0 + 1, y0)) +
         ay * ((1.0f - ax) * texel(l, x0, y0 + 1) + ax * texel(l, x0 + 1, y0 + 1));
}

glm::vec3 Texture::mean_over_triangle(const std::array<glm::vec2, 3>& uv) const {
  const Level& base = levels.front();
  const glm::vec2 scale(static_cast<float>(base.width), static_cast<float>(base.height));
  const glm::vec2 e1 = (uv[1] - uv[0]) * scale, e2 = (uv[2] - uv[0]) * scale;
  const float texels = 0.5f * std::abs(e1.x * e2.y - e1.y * e2.x);
  if (!std::isfinite(texels)) return mean;
  // k x k sub-triangles of equal area, one lookup at each centroid: up to 64
  // lookups, at the level where one texel is about one sub-triangle.
  constexpr int kMaxDivisions = 8;
  const int k = std::clamp(static_cast<int>(std::ceil(std::sqrt(texels))), 1, kMaxDivisions);
  const float per_lookup = texels / static_cast<float>(k * k);
  const int level =
      per_lookup > 1.0f ? static_cast<int>(std::round(0.5f * std::log2(per_lookup))) : 0;
  glm::vec3 sum(0.0f);
  const float inv = 1.0f / static_cast<float>(k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j) {
      const auto at = [&](float a, float b) {
        sum += lookup(uv[0] + a * inv * (uv[1] - uv[0]) + b * inv * (uv[2] - uv[0]), level);
      };
      at(static_cast<float>(i) + 1.0f / 3.0f, static_cast<float>(j) + 1.0f / 3.0f);
      if (i + j < k - 1)
        at(static_cast<float>(i) + 2.0f / 3.0f, static_cast<float>(j) + 2.0f / 3.0f);
    }
  return sum / static_cast<float>(k * k);
}

WeightedTexture::Parts WeightedTexture::lookup(glm::vec2 uv) const {
  return {glm::dvec3(weighted.lookup(uv)), static_cast<double>(weight.lookup(uv).x)};
}

WeightedTexture::Parts WeightedTexture::mean_over_triangle(
    const std::array<glm::vec2, 3>& uv) const {
  return {glm::dvec3(weighted.mean_over_triangle(uv)),
          static_cast<double>(weight.mean_over_triangle(uv).x)};
}

std::shared_ptr<const WeightedTexture> weighted_texture(const Texture& colour,
                                                        const std::vector<float>& weights) {
  auto out = std::make_shared<WeightedTexture>();
  const Texture::Level& base = colour.levels.front();
  Texture::Level weighted{base.width, base.height, {}}, weight{base.width, base.height, {}};
  weighted.texels.reserve(base.texels.size());
  weight.texels.reserve(base.texels.size());
  glm::dvec3 sum(0.0);
  double total = 0.0;
  for (std::size_t p = 0; p < base.texels.size(); ++p) {
    const float w = p < weights.size() && weights[p] > 0.0f ? weights[p] : 0.0f;
    weighted.texels.push_back(w * base.texels[p]);
    weight.texels.emplace_back(w);
    sum += glm::dvec3(weighted.texels.back());
    total += static_cast<double>(w);
  }
  out->mean = total > 0.0 ? glm::vec3(sum / total) : colour.mean;
  const auto texels = static_cast<double>(base.texels.size());
  const auto pyramid = [&](Texture& texture, Texture::Level level, const glm::dvec3& level_sum) {
    texture.source = colour.source;
    texture.mean = glm::vec3(level_sum / texels);
    texture.levels.push_back(std::move(level));
    while (texture.levels.back().width > 1 || texture.levels.back().height > 1)
      texture.levels.push_back(half(texture.levels.back()));
  };
  pyramid(out->weighted, std::move(weighted), sum);
  pyramid(out->weight, std::move(weight), glm::dvec3(total));
  return out;
}

std::optional<ImagePixels> read_image_pixels(const ImageSource& source, std::string& error) {
  const EmbeddedImage* embedded = source.embedded();
  if (embedded && embedded->raw()) return raw_pixels(*embedded, error);
  if (!embedded && !source.is_file()) {
    error = "the image has no file";
    return std::nullopt;
  }
  // An embedded image is decoded from memory; OpenImageIO picks its reader
  // by the name's extension first (then tries the others), so the name
  // carries the format the bytes are in.
  std::optional<OIIO::Filesystem::IOMemReader> memory;
  std::string name = source.file().string();
  if (embedded) {
    memory.emplace(embedded->bytes.data(), embedded->bytes.size());
    name = "embedded." + embedded_extension(*embedded);
  }
  // The colour as stored: OpenImageIO otherwise multiplies it by alpha
  // (PNG, TIFF, TGA, ...), which would blacken a cut-out's colour in and
  // next to its holes; a mask cuts where alpha says, and what remains is
  // the stored colour.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  // With a config, OpenImageIO 2.4's readers take the proxy from it (the
  // argument alone leaves them opening `name` as a file).
  OIIO::Filesystem::IOProxy* proxy = memory ? &*memory : nullptr;
  if (proxy) config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  auto in = OIIO::ImageInput::open(name, &config, proxy);
  if (!in) {
    const std::string why = one_line(OIIO::geterror());
    if (embedded)
      error = "OpenImageIO cannot decode the embedded " + embedded_extension(*embedded) + " image" +
              (why.empty() ? "" : ": " + why);
    else
      error = why.empty() ? "OpenImageIO cannot open it" : why;
    return std::nullopt;
  }
  const OIIO::ImageSpec& spec = in->spec();
  ImagePixels image;
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels;
  const int w = image.width, h = image.height, channels = image.channels;
  if (w <= 0 || h <= 0 || channels <= 0 || static_cast<long long>(w) * h > (1ll << 28)) {
    error = "unusable image size " + std::to_string(w) + " x " + std::to_string(h) + " x " +
            std::to_string(channels);
    return std::nullopt;
  }
  image.pixels.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) *
                      static_cast<std::size_t>(channels));
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, image.pixels.data())) {
    error = one_line(in->geterror());
    if (error.empty()) error = "OpenImageIO cannot read its pixels";
    return std::nullopt;
  }
  image.alpha_channel = spec.alpha_channel;
  if (image.alpha_channel >= 0 && image.alpha_channel < channels &&
      spec.get_int_attribute("oiio:UnassociatedAlpha", 0) == 0 &&
      stores_associated_alpha(in->format_name()))
    unassociate(image);
  // Integer images are sRGB unless the file says linear; float images are linear.
  const bool is_float = spec.format.basetype == OIIO::TypeDesc::FLOAT ||
                        spec.format.basetype == OIIO::TypeDesc::HALF ||
                        spec.format.basetype == OIIO::TypeDesc::DOUBLE;
  const std::string space = lower(spec.get_string_attribute("oiio:ColorSpace"));
  image.srgb = !is_float && space.find("linear") == std::string::npos;
  return image;
}

std::shared_ptr<const Texture> load_texture(const ImageSource& source, std::string& error,
                                            TexelKind kind) {
  const std::optional<ImagePixels> image = read_image_pixels(source, error);
  if (!image) return nullptr;
  const int w = image->width, h = image->height, channels = image->channels;
  const std::vector<float>& pixels = image->pixels;
  const bool srgb = image->srgb && kind == TexelKind::Colour;

  auto texture = std::make_shared<Texture>();
  texture->source = source;
  Texture::Level base;
  base.width = w;
  base.height = h;
  base.texels.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  glm::dvec3 sum(0.0);
  for (std::size_t p = 0; p < base.texels.size(); ++p) {
    const float* px = &pixels[p * static_cast<std::size_t>(channels)];
    glm::vec3 c = channels >= 3 ? glm::vec3(px[0], px[1], px[2]) : glm::vec3(px[0]);
    for (glm::length_t k = 0; k < 3; ++k) {
      if (!std::isfinite(c[k]) || c[k] < 0.0f) c[k] = 0.0f;
      if (srgb) c[k] = srgb_to_linear(c[k]);
    }
    base.texels[p] = c;
    sum += glm::dvec3(c);
  }
  texture->mean = glm::vec3(sum / static_cast<double>(base.texels.size()));
  texture->levels.push_back(std::move(base));
  while (texture->levels.back().width > 1 || texture->levels.back().height > 1)
    texture->levels.push_back(half(texture->levels.back()));
  return texture;
}

std::optional<fs::path> resolve_texture_path(const fs::path& folder, const std::string& name) {
  std::string portable = name;
  std::replace(portable.begin(), portable.end(), '\\', '/');
  const fs::path path = fs::path(portable).is_absolute() ? fs::path(portable) : folder / portable;
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) return path;
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  const std::string wanted = lower(path.filename().string());
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (lower(it->path().filename().string()) == wanted && it->is_regular_file(ec))
      return it->path();
  return std::nullopt;
}

}  // namespace bounce
