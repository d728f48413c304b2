#include "scene/ply_check.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene_loader.h"

namespace bounce::scene_internal {

namespace {

// A header longer than this is not a PLY header (Assimp keeps it in memory).
constexpr std::size_t kMaxHeaderLines = 100000;

// Assimp stores element and list counts in an unsigned int.
constexpr std::uint64_t kMaxAssimpCount = std::numeric_limits<std::uint32_t>::max();

// Digits the check accepts in one ascii number part. Assimp 5.2 parses
// integers with a wrapping 32-bit loop and the parts of a real with a 64-bit
// one that, on overflow, returns 0 *without moving past the digits*, so the
// next value would be read from the same digits (a list count read from a
// coordinate). 18 digits cannot overflow 64 bits.
constexpr std::size_t kMaxDigits = 18;

enum class ScalarKind { kUnsigned, kSigned, kReal };

struct PlyScalar {
  std::uint64_t bytes = 0;  // 0: not a PLY type
  ScalarKind kind = ScalarKind::kUnsigned;
};

PlyScalar scalar_type(const std::string& type) {
  if (type == "char" || type == "int8") return {1, ScalarKind::kSigned};
  if (type == "uchar" || type == "uint8") return {1, ScalarKind::kUnsigned};
  if (type == "short" || type == "int16") return {2, ScalarKind::kSigned};
  if (type == "ushort" || type == "uint16") return {2, ScalarKind::kUnsigned};
  if (type == "int" || type == "int32") return {4, ScalarKind::kSigned};
  if (type == "uint" || type == "uint32") return {4, ScalarKind::kUnsigned};
  if (type == "float" || type == "float32") return {4, ScalarKind::kReal};
  if (type == "double" || type == "float64") return {8, ScalarKind::kReal};
  return {};
}

struct PlyPropertyLayout {
  bool list = false;
  PlyScalar count;  // lists only
  PlyScalar item;
};

struct PlyElementLayout {
  std::string name;
  std::uint64_t count = 0;
  std::size_t line = 0;  // header line, 1-based
  std::vector<PlyPropertyLayout> properties;
};

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
  throw SceneLoader::LoadError(file.string(), "malformed PLY: " + what);
}

std::string printable(std::string_view text) {
  std::string shown(text.substr(0, 32));
  for (char& c : shown)
    if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
  return shown;
}

std::string on_line(std::size_t line) { return " on line " + std::to_string(line); }

// a * b + c without wrapping; saturates at the maximum.
std::uint64_t mul_add(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  constexpr auto kMax = std::numeric_limits<std::uint64_t>::max();
  if (b != 0 && a > (kMax - c) / b) return kMax;
  return a * b + c;
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Number of digits at the start of text.
std::size_t digit_run(std::string_view text) {
  std::size_t n = 0;
  while (n < text.size() && is_digit(text[n])) ++n;
  return n;
}

// Assimp 5.2 reads the count of an element only for the names it knows; for
// any other name it reads the count from the name itself (the digits it
// starts with), so "element 9999face 6" declares 9999 items to it and
// "element camera 1" none, and the body is misread from there on.
bool assimp_knows_element(const std::string& name) {
  return name == "vertex" || name == "face" || name == "tristrips" || name == "edge" ||
         name == "material";
}

// True if token is a number Assimp 5.2 reads as one whole value of this kind
// (its parsers stop at the first character they do not expect and the next
// value starts there, so anything else could shift every later value).
bool whole_ascii_value(std::string_view t, ScalarKind kind) {
  std::size_t i = 0;
  if (kind != ScalarKind::kUnsigned && i < t.size() && (t[i] == '-' || t[i] == '+')) ++i;
  std::size_t n = digit_run(t.substr(i));
  if (n == 0 || n > kMaxDigits) return false;
  i += n;
  if (kind != ScalarKind::kReal) return i == t.size();
  if (i < t.size() && t[i] == '.') {
    n = digit_run(t.substr(i + 1));
    if (n == 0 || n > kMaxDigits) return false;
    i += 1 + n;
  }
  if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
    ++i;
    if (i < t.size() && (t[i] == '-' || t[i] == '+')) ++i;
    n = digit_run(t.substr(i));
    if (n == 0 || n > kMaxDigits) return false;
    i += n;
  }
  return i == t.size();
}

// The value of a token whole_ascii_value accepted as an integer.
std::int64_t integer_value(std::string_view t) {
  std::size_t i = 0;
  bool negative = false;
  if (t[0] == '-' || t[0] == '+') {
    negative = t[0] == '-';
    i = 1;
  }
  std::int64_t value = 0;
  for (; i < t.size(); ++i) value = value * 10 + (t[i] - '0');
  return negative ? -value : value;
}

// Words of an ascii body line as Assimp splits them (spaces and tabs only).
void split_words(std::string_view line, std::vector<std::string_view>& words) {
  words.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
}

std::string item_of(const PlyElementLayout& element, std::uint64_t index) {
  return "element '" + element.name + "' item " + std::to_string(index) + " of " +
         std::to_string(element.count);
}

// The ascii body, one line per element item as the format (and Assimp, which
// reads each item from its own line) requires. Every value must be a whole
// number of its type and every list as long as its count says, so each count
// Assimp allocates for is backed by values in the file.
void check_ascii_body(const std::filesystem::path& file, std::istream& in,
                      const std::vector<PlyElementLayout>& elements, std::size_t header_lines) {
  std::string line;
  std::vector<std::string_view> words;
  std::size_t line_number = header_lines;
  for (const PlyElementLayout& element : elements) {
    for (std::uint64_t index = 0; index < element.count; ++index) {
      if (!std::getline(in, line))
        fail(file, "truncated: the file ends before " + item_of(element, index) +
                       " (the header declares it on line " + std::to_string(element.line) + ")");
      ++line_number;
      // Assimp 5.2 reads a last line without a line end together with
      // leftovers of the longer line before it ("4 0 1 2 3" after
      // "0 1 0.0e+0" became "4 0 1 2 30"), which could lengthen a count.
      if (in.eof())
        fail(file, "the last line of the ascii data (line " + std::to_string(line_number) +
                       ") has no line end");
      if (!line.empty() && line.back() == '\r') line.pop_back();
      for (const char c : line)
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t')
          fail(file, "control character " + std::to_string(static_cast<int>(c)) +
                         on_line(line_number) + " of the ascii data");
      split_words(line, words);
      std::size_t next = 0;
      for (const PlyPropertyLayout& property : element.properties) {
        std::uint64_t values = 1;
        PlyScalar type = property.item;
        if (property.list) {
          if (next >= words.size() || !whole_ascii_value(words[next], property.count.kind))
            fail(file, item_of(element, index) + on_line(line_number) + " has no valid list count");
          const std::int64_t count = integer_value(words[next]);
          ++next;
          if (count < 0 || static_cast<std::uint64_t>(count) > words.size() - next)
            fail(file, item_of(element, index) + on_line(line_number) + " has a list count of " +
                           std::to_string(count) + " but " + std::to_string(words.size() - next) +
                           " values after it");
          values = static_cast<std::uint64_t>(count);
        }
        for (std::uint64_t v = 0; v < values; ++v, ++next) {
          if (next >= words.size())
            fail(file, item_of(element, index) + on_line(line_number) +
                           " has fewer values than its properties");
          if (!whole_ascii_value(words[next], type.kind))
            fail(file, "'" + printable(words[next]) + "'" + on_line(line_number) + " (" +
                           item_of(element, index) + ") is not a whole " +
                           (type.kind == ScalarKind::kReal ? "number" : "integer") +
                           " of its type");
        }
      }
      if (next != words.size())
        fail(file, item_of(element, index) + on_line(line_number) + " has " +
                       std::to_string(words.size()) + " values, its properties take " +
                       std::to_string(next));
    }
  }
}

// Reads the binary body in blocks and walks it item by item.
class BinaryBodyReader {
 public:
  BinaryBodyReader(std::istream& in, std::uint64_t size) : in_(in), remaining_(size) {}
  std::uint64_t remaining() const { return remaining_; }
  // Skips n bytes the caller has checked are there.
  void skip(std::uint64_t n) {
    const std::uint64_t buffered = buffer_.size() - position_;
    if (n <= buffered) {
      position_ += n;
    } else {
      in_.seekg(static_cast<std::streamoff>(n - buffered), std::ios::cur);
      buffer_.clear();
      position_ = 0;
    }
    remaining_ -= n;
  }
  // Reads a count of `bytes` bytes (checked to be there) as Assimp converts
  // it to unsigned int; -1 for a negative signed value.
  std::int64_t read_count(const PlyScalar& type, bool big_endian) {
    unsigned char raw[8] = {};
    for (std::uint64_t i = 0; i < type.bytes; ++i) raw[i] = next_byte();
    remaining_ -= type.bytes;
    std::uint64_t value = 0;
    for (std::uint64_t i = 0; i < type.bytes; ++i) {
      const std::uint64_t byte = raw[big_endian ? i : type.bytes - 1 - i];
      value = (value << 8) | byte;
    }
    const std::uint64_t sign_bit = std::uint64_t{1} << (8 * type.bytes - 1);
    if (type.kind == ScalarKind::kSigned && (value & sign_bit) != 0) return -1;
    return static_cast<std::int64_t>(value);
  }

 private:
  unsigned char next_byte() {
    if (position_ == buffer_.size()) {
      buffer_.resize(static_cast<std::size_t>(std::min<std::uint64_t>(remaining_, 1 << 16)));
      in_.read(reinterpret_cast<char*>(buffer_.data()),
               static_cast<std::streamsize>(buffer_.size()));
      buffer_.resize(static_cast<std::size_t>(in_.gcount()));
      position_ = 0;
      if (buffer_.empty()) return 0;  // cannot happen: the size was measured
    }
    return buffer_[position_++];
  }

  std::istream& in_;
  std::uint64_t remaining_;
  std::vector<unsigned char> buffer_;
  std::size_t position_ = 0;
};

// The binary body: every fixed-size item and every list must fit in the bytes
// that are left, so no count Assimp allocates for exceeds the file.
void check_binary_body(const std::filesystem::path& file, std::istream& in, std::uint64_t size,
                       bool big_endian, const std::vector<PlyElementLayout>& elements) {
  BinaryBodyReader body(in, size);
  for (const PlyElementLayout& element : elements) {
    bool has_list = false;
    std::uint64_t fixed = 0;
    for (const PlyPropertyLayout& property : element.properties) {
      has_list = has_list || property.list;
      if (!property.list) fixed += property.item.bytes;
    }
    if (!has_list) {
      const std::uint64_t needed = mul_add(element.count, fixed, 0);
      if (needed > body.remaining())
        fail(file, "truncated: element '" + element.name + "' (line " +
                       std::to_string(element.line) + ") declares " +
                       std::to_string(element.count) + " items of " + std::to_string(fixed) +
                       " bytes, the file holds " + std::to_string(body.remaining()) +
                       " more bytes");
      body.skip(needed);
      continue;
    }
    for (std::uint64_t index = 0; index < element.count; ++index) {
      for (const PlyPropertyLayout& property : element.properties) {
        const PlyScalar& head = property.list ? property.count : property.item;
        if (head.bytes > body.remaining())
          fail(file, "truncated: the file ends inside " + item_of(element, index));
        if (!property.list) {
          body.skip(head.bytes);
          continue;
        }
        const std::int64_t count = body.read_count(head, big_endian);
        if (count < 0) fail(file, item_of(element, index) + " has a negative list count");
        const std::uint64_t bytes =
            mul_add(static_cast<std::uint64_t>(count), property.item.bytes, 0);
        if (bytes > body.remaining())
          fail(file, item_of(element, index) + " has a list of " + std::to_string(count) +
                         " values, the file holds " + std::to_string(body.remaining()) +
                         " more bytes");
        body.skip(bytes);
      }
    }
  }
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
  bool binary = false, big_endian = false, have_format = false, ended = false, crlf = false;
  std::vector<PlyElementLayout> elements;
  std::size_t n = 0;
  for (; n < kMaxHeaderLines && std::getline(in, line); ++n) {
    const std::size_t line_number = n + 1;
    if (!line.empty() && line.back() == '\r') {
      line.pop_back();
      crlf = true;
    }
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
        fail(file,
             "the 'end_header' line has more on it (line " + std::to_string(line_number) + ")");
      ended = true;
      break;
    }
    if (keyword != "format" && keyword != "element" && keyword != "property" &&
        keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
      // The PLY header has no other keywords. Assimp 5.2 does not skip
      // unknown lines safely: fuzzing found a header with damaged 'property'
      // lines that corrupts its heap (tests/fuzz/regressions).
      fail(file, "unknown header keyword '" + printable(keyword) + "'" + on_line(line_number));
    }
    // Assimp 5.2 also ends header lines at CR, NUL and form feed, and splits
    // words only at spaces and tabs: refuse what it would read differently.
    for (const char c : line)
      if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f)
        fail(file, "control character " + std::to_string(static_cast<int>(c)) + " in the header" +
                       on_line(line_number));
    if (keyword.empty()) {
      // Assimp ends an element's property list at an empty line and drops the
      // properties after it, which would shift the whole body.
      fail(file, "empty header line" + on_line(line_number));
    } else if (keyword == "format") {
      std::string format;
      words >> format;
      if (format == "ascii") {
        binary = false;
      } else if (format == "binary_little_endian" || format == "binary_big_endian") {
        binary = true;
        big_endian = format == "binary_big_endian";
      } else {
        fail(file, "unknown format '" + printable(format) + "'" + on_line(line_number));
      }
      have_format = true;
    } else if (keyword == "element") {
      std::string name, count;
      words >> name >> count;
      // Assimp 5.2 reads the count of any other element from its name (see
      // assimp_knows_element): "element 99999999999999face 6" made it allocate 31 GB
      // (fuzzing, CI). Such elements cannot be read correctly, so refuse them.
      if (!assimp_knows_element(name))
        fail(file, "element '" + printable(name) + "'" + on_line(line_number) +
                       " is not one the PLY reader (Assimp 5.2) can read: "
                       "vertex, face, tristrips, edge, material");
      if (count.empty() || count.find_first_not_of("0123456789") != std::string::npos ||
          count.size() > 19)
        fail(file, "element '" + name + "' has no valid count" + on_line(line_number));
      if (std::stoull(count) > kMaxAssimpCount)
        fail(file, "element '" + name + "' declares " + count + " items" + on_line(line_number) +
                       ", more than the PLY reader (Assimp 5.2) can count (" +
                       std::to_string(kMaxAssimpCount) + ")");
      // Assimp 5.2 reads every element of one name into one array sized by
      // the first: a second, longer "element vertex" wrote past its end
      // (fuzzing: heap corruption in the uninstrumented library).
      for (const PlyElementLayout& earlier : elements)
        if (earlier.name == name)
          fail(file, "element '" + name + "' is declared twice (lines " +
                         std::to_string(earlier.line) + " and " + std::to_string(line_number) +
                         "): the PLY reader (Assimp 5.2) would read both into one array");
      elements.push_back({name, std::stoull(count), line_number, {}});
    } else if (keyword == "property") {
      if (elements.empty()) fail(file, "property before any element" + on_line(line_number));
      std::string type, name;
      words >> type;
      PlyPropertyLayout property;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        property.list = true;
        property.count = scalar_type(count_type);
        property.item = scalar_type(item_type);
        if (property.count.bytes == 0 || property.count.kind == ScalarKind::kReal ||
            property.item.bytes == 0)
          fail(file, "unknown list types '" + printable(count_type) + " " + printable(item_type) +
                         "'" + on_line(line_number));
      } else {
        property.item = scalar_type(type);
        if (property.item.bytes == 0)
          fail(file, "unknown property type '" + printable(type) + "'" + on_line(line_number));
      }
      // Assimp drops a property without a name, shifting the body.
      words >> name;
      if (name.empty()) fail(file, "property without a name" + on_line(line_number));
      elements.back().properties.push_back(property);
    }
  }
  if (!ended) fail(file, "the header has no 'end_header' line");
  if (!have_format) fail(file, "the header has no 'format' line");
  for (const PlyElementLayout& element : elements)
    if (element.properties.empty() && element.count > 0)
      fail(file, "element '" + element.name + "' (line " + std::to_string(element.line) +
                     ") declares " + std::to_string(element.count) + " items but no properties");
  if (!binary) {
    check_ascii_body(file, in, elements, n + 1);
    return;
  }
  // Assimp 5.2 starts a binary body right after the CR of "end_header\r\n",
  // one byte before the data.
  if (crlf) fail(file, "binary PLY with CR LF line ends in its header");
  const std::streamoff body_start = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  if (body_start < 0 || end < body_start) fail(file, "cannot measure the file");
  in.seekg(body_start);
  check_binary_body(file, in, static_cast<std::uint64_t>(end - body_start), big_endian, elements);
}

}  // namespace bounce::scene_internal
