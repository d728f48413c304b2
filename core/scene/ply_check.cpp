#include "scene/ply_check.h"

#include <cctype>
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
  std::uint64_t minimum_body = 0;  // bytes, binary formats only
  // Bytes, ascii: Assimp 5.2 allocates for the declared counts before it
  // reads the body, so a 300-byte file declaring 2e13 faces asked for 63 GB
  // (fuzzing: out of memory).
  std::uint64_t minimum_ascii_body = 0;
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
      // The body starts right after "end_header\n". Assimp 5.2 spent minutes
      // (fuzzing: > 10 s per input) on "end_header" followed by other
      // whitespace and the body on the same line.
      if (line != "end_header")
        fail(file, "the 'end_header' line has more on it (line " + std::to_string(n + 1) + ")");
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
      // In ascii every value is at least one character and a separator.
      minimum_ascii_body = mul_add(element_count, 2, minimum_ascii_body);
    } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
      // The PLY header has no other keywords. Assimp 5.2 does not skip
      // unknown lines safely: fuzzing found a header with damaged 'property'
      // lines that corrupts its heap (tests/fuzz/regressions).
      std::string shown = keyword.substr(0, 32);
      for (char& c : shown)
        if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
      fail(file, "unknown header keyword '" + shown + "' on line " + std::to_string(n + 1));
    }
  }
  if (!ended) fail(file, "the header has no 'end_header' line");
  if (!have_format) fail(file, "the header has no 'format' line");
  const std::streamoff body_start = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  if (body_start < 0 || end < body_start) fail(file, "cannot measure the file");
  const auto body = static_cast<std::uint64_t>(end - body_start);
  if (!binary) {
    // The last value may end the file without a separator.
    if (body + 1 < minimum_ascii_body)
      fail(file, "truncated: the header declares values needing at least " +
                     std::to_string(minimum_ascii_body - 1) +
                     " bytes of ascii data, the file "
                     "holds " +
                     std::to_string(body));
    return;
  }
  if (body < minimum_body)
    fail(file, "truncated: the header declares at least " + std::to_string(minimum_body) +
                   " bytes of binary data, the file holds " + std::to_string(body));
}

}  // namespace bounce::scene_internal
