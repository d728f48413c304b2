#include "scene/image_source.h"

#include <fstream>
#include <iterator>

namespace bounce {

std::filesystem::path ImageSource::file() const {
  const auto* file = std::get_if<std::filesystem::path>(&where_);
  return file ? *file : std::filesystem::path();
}

const EmbeddedImage* ImageSource::embedded() const {
  const auto* image = std::get_if<Embedded>(&where_);
  return image ? image->get() : nullptr;
}

std::string ImageSource::name() const {
  if (const auto* file = std::get_if<std::filesystem::path>(&where_)) return file->string();
  if (const EmbeddedImage* image = embedded()) return image->name;
  return "(none)";
}

bool operator==(const ImageSource& a, const ImageSource& b) {
  const EmbeddedImage *x = a.embedded(), *y = b.embedded();
  if (x && y)
    return x == y || (x->name == y->name && x->raw_width == y->raw_width &&
                      x->raw_height == y->raw_height && x->bytes == y->bytes);
  return a.where_ == b.where_;
}

std::vector<std::uint8_t> image_file_bytes(const ImageSource& source, std::string& error) {
  if (const EmbeddedImage* image = source.embedded()) {
    if (image->raw()) {
      error = "the embedded image is raw texels, not an image file";
      return {};
    }
    if (image->bytes.empty()) error = "the embedded image is empty";
    return image->bytes;
  }
  if (!source.is_file()) {
    error = "the image has no file";
    return {};
  }
  std::ifstream in(source.file(), std::ios::binary);
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
  if (!in.is_open() || (!in.good() && !in.eof())) {
    error = "cannot read the file";
    return {};
  }
  if (bytes.empty()) error = "the file is empty";
  return bytes;
}

}  // namespace bounce
