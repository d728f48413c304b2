#include "scene/ply_check.h"

#include <cstdint>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "scene/scene_loader.h"

namespace bounce::scene_internal {

namespace {

// A header longer than this is not a PLY header (Assimp keeps it in memory).
constexpr std::size_t kMaxHeaderLines = 100000;

// Size in bytes of a PLY scalar type, 0 if the name is not one.
std::uint64_t scalar_size(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" ||
      type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
  throw SceneLoader::LoadError(file.string(), "malformed PLY: " + what);
}

// a * b + c without wrapping; saturates at the maximum.
std::uint64_t mul_add(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  constexpr auto kMax = std::numeric_limits<std::uint64_t>::max();
  if (b != 0 && a > (kMax - c) / b) return kMax;
  return a * b + c;
}

}  // namespace

bool looks_like_ply(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  return in.gcount() == 4 && magic[0] == 'p' && magic[1] == 'l' && magic[2] == 'y' &&
         (magic[3] == '\n' || magic[3] == '\r' || magic[3] == ' ');
}

void check_ply_structure(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(file, "cannot open");
  std::string line;
  bool binary = false, have_format = false, ended = false;
  std::uint64_t minimum_body = 0;   // bytes, binary formats only
  std::uint64_t element_count = 0;  // of the element whose properties are being read
  bool in_element = false;
  for (std::size_t n = 0; n < kMaxHeaderLines && std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (n == 0) {
      if (keyword != "ply") fail(file, "the first line is not 'ply'");
      continue;
    }
    if (keyword == "end_header") {
      ended = true;
      break;
    }
    if (keyword == "format") {
      std::string format;
      words >> format;
      if (format == "ascii") {
        binary = false;
      } else if (format == "binary_little_endian" || format == "binary_big_endian") {
        binary = true;
      } else {
        fail(file, "unknown format '" + format + "' on line " + std::to_string(n + 1));
      }
      have_format = true;
    } else if (keyword == "element") {
      std::string name, count;
      words >> name >> count;
      if (count.empty() || count.find_first_not_of("0123456789") != std::string::npos ||
          count.size() > 19)
        fail(file, "element '" + name + "' has no valid count on line " + std::to_string(n + 1));
      element_count = std::stoull(count);
      in_element = true;
    } else if (keyword == "property") {
      if (!in_element) fail(file, "property before any element on line " + std::to_string(n + 1));
      std::string type;
      words >> type;
      std::uint64_t bytes = 0;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        bytes = scalar_size(count_type);  // an empty list still stores its count
        if (bytes == 0 || scalar_size(item_type) == 0)
          fail(file, "unknown list types '" + count_type + " " + item_type + "' on line " +
                         std::to_string(n + 1));
      } else {
        bytes = scalar_size(type);
        if (bytes == 0)
          fail(file, "unknown property type '" + type + "' on line " + std::to_string(n + 1));
      }
      minimum_body = mul_add(element_count, bytes, minimum_body);
    }
    // comment, obj_info and anything else: Assimp skips them too.
  }
  if (!ended) fail(file, "the header has no 'end_header' line");
  if (!have_format) fail(file, "the header has no 'format' line");
  if (!binary) return;
  const std::streamoff body_start = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  if (body_start < 0 || end < body_start) fail(file, "cannot measure the file");
  const auto body = static_cast<std::uint64_t>(end - body_start);
  if (body < minimum_body)
    fail(file, "truncated: the header declares at least " + std::to_string(minimum_body) +
                   " bytes of binary data, the file holds " + std::to_string(body));
}

}  // namespace bounce::scene_internal
