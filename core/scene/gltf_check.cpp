#include "scene/gltf_check.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>

#include <nlohmann/json.hpp>

#include "scene/scene_loader.h"

namespace bounce::scene_internal {

namespace {

using nlohmann::json;

[[noreturn]] void refuse(const std::filesystem::path& file, const std::string& what) {
  throw SceneLoader::LoadError(file.string(), "malformed glTF: " + what);
}

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool has_binary_magic(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::array<char, 4> magic{};
  return in.read(magic.data(), magic.size()) && std::memcmp(magic.data(), "glTF", 4) == 0;
}

std::uint32_t little_u32(const char* bytes) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = v << 8 | static_cast<unsigned char>(bytes[i]);
  return v;
}

// The JSON text: the whole file, or a binary file's first chunk, which the
// format requires to be the JSON one. Of a binary file only the headers and
// that chunk are read: its binary chunk (meshes, images) may be most of the
// file, and Assimp reads it next anyway.
std::string json_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneLoader::LoadError(file.string(), "cannot open the file");
  // A 12-byte header, then chunks of (length, type, data).
  std::array<char, 20> head{};
  in.read(head.data(), head.size());
  const auto got = static_cast<std::size_t>(in.gcount());
  if (got < 4 || std::memcmp(head.data(), "glTF", 4) != 0) {
    in.clear();
    in.seekg(0);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  if (got < head.size()) refuse(file, "the binary header and first chunk header are cut short");
  const std::uint32_t length = little_u32(head.data() + 12), type = little_u32(head.data() + 16);
  if (type != 0x4E4F534Au) refuse(file, "the first chunk of a binary glTF is not its JSON chunk");
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  const std::uintmax_t after = ec ? 0 : size - head.size();
  if (length > after)
    refuse(file, "the JSON chunk declares " + std::to_string(length) + " bytes, the file holds " +
                     std::to_string(after) + " after the headers");
  std::string text(length, '\0');
  in.read(text.data(), static_cast<std::streamsize>(length));
  if (static_cast<std::uint32_t>(in.gcount()) != length)
    refuse(file, "the JSON chunk is cut short");
  return text;
}

// Index `key` of `object`, when present: an unsigned integer below `count`.
bool accessor_index(const json& object, const char* key, std::size_t count, std::size_t& out) {
  const auto it = object.find(key);
  if (it == object.end()) return false;
  if (!it->is_number_unsigned() || it->get<std::uint64_t>() >= count) return false;
  out = static_cast<std::size_t>(it->get<std::uint64_t>());
  return true;
}

// Refuses an image whose media type has no '/'.
void check_image_media_types(const std::filesystem::path& file, const json& doc) {
  const auto images = doc.find("images");
  if (images == doc.end() || !images->is_array()) return;
  for (std::size_t i = 0; i < images->size(); ++i) {
    const json& image = (*images)[i];
    if (!image.is_object()) continue;
    // The media type: `mimeType`, or the one a data URI names before its
    // first ';' or ','. Assimp reads the part after its '/' without looking
    // for one (a crash, found by fuzzing), so one without is refused here.
    std::string type;
    if (const auto m = image.find("mimeType"); m != image.end()) {
      if (!m->is_string()) refuse(file, "images[" + std::to_string(i) + "]'s mimeType is not text");
      type = m->get<std::string>();
    } else if (const auto u = image.find("uri"); u != image.end() && u->is_string()) {
      const std::string& uri = u->get_ref<const std::string&>();
      if (uri.rfind("data:", 0) != 0) continue;
      type = uri.substr(5, uri.find_first_of(";,", 5) - 5);
      if (type.empty()) continue;  // a data URI may leave its type out
    } else {
      continue;
    }
    if (type.find('/') == std::string::npos)
      refuse(file, "images[" + std::to_string(i) + "]'s media type '" + type +
                       "' is not a type/subtype such as image/png");
  }
}

}  // namespace

bool looks_like_gltf(const std::filesystem::path& file) {
  const std::string ext = lower_extension(file);
  return ext == ".gltf" || ext == ".glb" || has_binary_magic(file);
}

void check_gltf_structure(const std::filesystem::path& file) {
  json doc;
  try {
    doc = json::parse(json_text(file));
  } catch (const json::exception& e) {  // parse errors, and numbers out of range
    refuse(file, std::string("not valid UTF-8 JSON: ") + e.what());
  }
  if (!doc.is_object()) refuse(file, "the top level is not a JSON object");
  check_image_media_types(file, doc);
  const auto accessors_it = doc.find("accessors");
  const json no_accessors = json::array();
  const json& accessors =
      accessors_it != doc.end() && accessors_it->is_array() ? *accessors_it : no_accessors;
  const auto meshes = doc.find("meshes");
  if (meshes == doc.end()) return;
  if (!meshes->is_array()) refuse(file, "'meshes' is not an array");
  for (std::size_t m = 0; m < meshes->size(); ++m) {
    const json& mesh = (*meshes)[m];
    const auto primitives = mesh.is_object() ? mesh.find("primitives") : mesh.end();
    if (!mesh.is_object() || primitives == mesh.end() || !primitives->is_array())
      refuse(file, "mesh " + std::to_string(m) + " has no 'primitives' array");
    for (std::size_t p = 0; p < primitives->size(); ++p) {
      const json& primitive = (*primitives)[p];
      const std::string where = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
      const auto attributes =
          primitive.is_object() ? primitive.find("attributes") : primitive.end();
      if (!primitive.is_object() || attributes == primitive.end() || !attributes->is_object())
        refuse(file, where + " has no 'attributes' object");
      // The vertices' accessor, and the indices' when there are any: each
      // must exist and hold at least one element.
      const auto check_accessor = [&](const json& owner, const char* key, bool required) {
        if (!required && !owner.contains(key)) return;
        std::size_t a = 0;
        if (!accessor_index(owner, key, accessors.size(), a))
          refuse(file, where + (owner.contains(key)
                                    ? "'s " + std::string(key) + " names no accessor of the " +
                                          std::to_string(accessors.size())
                                    : " has no " + std::string(key) + " attribute (its vertices)"));
        const json& accessor = accessors[a];
        const auto count = accessor.is_object() ? accessor.find("count") : accessor.end();
        if (count == accessor.end() || !count->is_number_unsigned() ||
            count->get<std::uint64_t>() == 0)
          refuse(file,
                 where + "'s " + key + " accessor " + std::to_string(a) + " holds no elements");
      };
      check_accessor(*attributes, "POSITION", true);
      check_accessor(primitive, "indices", false);
    }
  }
}

}  // namespace bounce::scene_internal
