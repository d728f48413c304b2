#pragma once
// Where a material's image comes from: a file on disk, or an image embedded
// in the mesh file (a .glb's bufferView, a .gltf's data URI: Assimp names
// them "*0", "*1", ...) held in memory. Everything that reads a texture,
// mask or normal map takes an ImageSource, so an embedded image is decoded,
// sampled and exported exactly as a file is; only the bytes' origin differs.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace bounce {

// An image embedded in a mesh file, as the file stores it.
struct EmbeddedImage {
  // For messages: the mesh file and the image's index in it,
  // "/models/scene.glb#texture 0".
  std::string name;
  // Encoded image file bytes (PNG, JPEG, ...) when raw_width is 0;
  // otherwise raw_width x raw_height RGBA8 texels, row 0 at the top (formats
  // that embed uncompressed pixels).
  std::vector<std::uint8_t> bytes;
  // The file format's extension as the mesh file hints it ("png", "jpg"),
  // empty when it does not say.
  std::string format_hint;
  int raw_width = 0, raw_height = 0;
  bool raw() const { return raw_width > 0; }
};

class ImageSource {
 public:
  ImageSource() = default;  // none: an image made in memory (a constant mask)
  // A file is the common case, hence implicit.
  ImageSource(std::filesystem::path file) : where_(std::move(file)) {}  // NOLINT
  explicit ImageSource(std::shared_ptr<const EmbeddedImage> image) : where_(std::move(image)) {}

  bool is_file() const { return std::holds_alternative<std::filesystem::path>(where_); }
  bool is_embedded() const { return std::holds_alternative<Embedded>(where_); }
  // The file; empty unless is_file().
  std::filesystem::path file() const;
  // The embedded image; null unless is_embedded().
  const EmbeddedImage* embedded() const;
  // What messages, manifests and caches call it: the file's path, or the
  // embedded image's name; "(none)" for no source.
  std::string name() const;

  // The same file, or the same embedded image (the same bytes under the same
  // name: one mesh file read twice still shares its images).
  friend bool operator==(const ImageSource& a, const ImageSource& b);

 private:
  using Embedded = std::shared_ptr<const EmbeddedImage>;
  std::variant<std::monostate, std::filesystem::path, Embedded> where_;
};

// The image's bytes as stored: the file read whole, or the embedded
// (encoded) bytes. Empty, with `error` set (the reason, without the
// source's name), when the file cannot be read, is empty, or the embedded
// image is raw texels rather than an image file.
std::vector<std::uint8_t> image_file_bytes(const ImageSource& source, std::string& error);

}  // namespace bounce
