#include "scene/json_reader.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "scene/scene_loader.h"

namespace bounce::scene_internal {

TextPosition position_of_index(std::string_view text, std::size_t index) {
  index = std::min(index, text.size());
  TextPosition pos;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < index; ++i) {
    if (text[i] == '\n') {
      ++pos.line;
      line_start = i + 1;
    }
  }
  pos.column = index - line_start + 1;
  return pos;
}

std::string join_key(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

std::string join_index(const std::string& parent, std::size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

JsonReader::JsonReader(std::string file, Diagnostics& diagnostics)
    : file_(std::move(file)), diagnostics_(diagnostics) {}

namespace {

// nlohmann's messages read "[json.exception.parse_error.101] parse error at
// line 3, column 5: syntax error while parsing ..."; keep only what follows
// the position, since we print the position ourselves in file:line:col form.
std::string strip_nlohmann_prefix(const std::string& what) {
  const std::size_t column = what.find("column ");
  if (column != std::string::npos) {
    const std::size_t colon = what.find(": ", column);
    if (colon != std::string::npos) return what.substr(colon + 2);
  }
  const std::size_t bracket = what.find("] ");
  return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

std::string file_name_of(const std::string& file) {
  const std::size_t slash = file.find_last_of('/');
  return slash == std::string::npos ? file : file.substr(slash + 1);
}

// Tracks where the parser is (as a key path) to name duplicate keys, which
// nlohmann would otherwise resolve silently by keeping the last value.
class DuplicateKeyWatcher {
 public:
  static constexpr int kMaxDepth = 64;

  explicit DuplicateKeyWatcher(const JsonReader& reader) : reader_(reader) {}

  bool operator()(int depth, nlohmann::json::parse_event_t event, Json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        // Each frame holds its full key path, so nesting costs depth^2; a
        // hostile file 100000 levels deep took minutes (found by the hostile
        // input tests). No scene.json needs more than a few levels.
        if (depth >= kMaxDepth)
          reader_.fail(child_path(), "nested deeper than " + std::to_string(kMaxDepth) +
                                         " levels; a scene.json needs at most a few");
        frames_.push_back({event == Event::object_start, child_path(), {}, {}, 0});
        break;
      case Event::object_end:
      case Event::array_end:
        if (!frames_.empty()) frames_.pop_back();
        break;
      case Event::key: {
        Frame& frame = frames_.back();
        frame.key = parsed.get<std::string>();
        if (!frame.keys.insert(frame.key).second)
          reader_.warn(join_key(frame.path, frame.key),
                       "duplicate key; the last value given is used");
        break;
      }
      case Event::value:
        if (!frames_.empty() && !frames_.back().is_object) ++frames_.back().index;
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool is_object;
    std::string path;
    std::set<std::string> keys;
    std::string key;    // objects: the key whose value is being read
    std::size_t index;  // arrays: index of the next element
  };

  // Path of the object or array that starts now, relative to the open frame.
  std::string child_path() {
    if (frames_.empty()) return {};
    Frame& parent = frames_.back();
    if (parent.is_object) return join_key(parent.path, parent.key);
    return join_index(parent.path, parent.index++);
  }

  const JsonReader& reader_;
  std::vector<Frame> frames_;
};

}  // namespace

Json JsonReader::parse(const std::string& text) const {
  const std::string name = file_name_of(file_);
  DuplicateKeyWatcher watcher(*this);
  try {
    return Json::parse(text, std::ref(watcher));
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte counts the characters read, including the offending one.
    const TextPosition pos = position_of_index(text, e.byte == 0 ? 0 : e.byte - 1);
    throw SceneLoader::LoadError(file_, name + ":" + std::to_string(pos.line) + ":" +
                                            std::to_string(pos.column) + ": " +
                                            strip_nlohmann_prefix(e.what()));
  } catch (const nlohmann::json::exception& e) {
    // Number overflow ("1e999") carries no position; find the literal it quotes.
    const std::string what = strip_nlohmann_prefix(e.what());
    const std::size_t open = what.find('\'');
    const std::size_t close = what.rfind('\'');
    if (open != std::string::npos && close > open + 1) {
      const std::size_t at = text.find(what.substr(open + 1, close - open - 1));
      if (at != std::string::npos) {
        const TextPosition pos = position_of_index(text, at);
        throw SceneLoader::LoadError(file_, name + ":" + std::to_string(pos.line) + ":" +
                                                std::to_string(pos.column) + ": " + what);
      }
    }
    throw SceneLoader::LoadError(file_, name + ": " + what);
  }
}

void JsonReader::fail(const std::string& key_path, const std::string& what) const {
  throw SceneLoader::LoadError(file_, key_path.empty() ? what : key_path + ": " + what);
}

void JsonReader::warn(const std::string& key_path, const std::string& what) const {
  diagnostics_.warn(file_, key_path.empty() ? what : key_path + ": " + what);
}

void JsonReader::warn_unknown_keys(const Json& object, const std::string& path,
                                   std::initializer_list<std::string_view> known) const {
  for (const auto& item : object.items()) {
    bool found = false;
    for (std::string_view k : known) found = found || item.key() == k;
    if (!found) warn(join_key(path, item.key()), "unknown key, ignored");
  }
}

std::string JsonReader::describe(const Json& value) {
  switch (value.type()) {
    case Json::value_t::null:
      return "null";
    case Json::value_t::boolean:
      return std::string("a boolean (") + (value.get<bool>() ? "true" : "false") + ")";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float:
      return "a number (" + value.dump() + ")";
    case Json::value_t::string: {
      std::string s = value.dump();
      if (s.size() > 42) s = s.substr(0, 40) + "...\"";
      return "a string (" + s + ")";
    }
    case Json::value_t::array:
      return "an array of " + std::to_string(value.size()) +
             (value.size() == 1 ? " element" : " elements");
    case Json::value_t::object:
      return "an object";
    default:
      return "an unsupported value";
  }
}

void JsonReader::expect_object(const Json& value, const std::string& path) const {
  if (!value.is_object()) fail(path, "expected an object, got " + describe(value));
}

void JsonReader::expect_array(const Json& value, const std::string& path) const {
  if (!value.is_array()) fail(path, "expected an array, got " + describe(value));
}

double JsonReader::number(const Json& value, const std::string& path) const {
  if (!value.is_number()) fail(path, "expected a number, got " + describe(value));
  const double v = value.get<double>();
  if (!std::isfinite(v)) fail(path, "expected a finite number, got " + value.dump());
  return v;
}

float JsonReader::number_f(const Json& value, const std::string& path) const {
  const double v = number(value, path);
  if (std::abs(v) > static_cast<double>(std::numeric_limits<float>::max()))
    fail(path, "number " + value.dump() + " is out of range for a 32-bit float");
  return static_cast<float>(v);
}

long long JsonReader::integer(const Json& value, const std::string& path, long long lo,
                              long long hi) const {
  const std::string range =
      "an integer between " + std::to_string(lo) + " and " + std::to_string(hi);
  if (!value.is_number()) fail(path, "expected " + range + ", got " + describe(value));
  long long v = 0;
  if (value.is_number_unsigned()) {
    const auto u = value.get<unsigned long long>();
    if (u > static_cast<unsigned long long>(hi))
      fail(path, "expected " + range + ", got " + value.dump());
    v = static_cast<long long>(u);
  } else if (value.is_number_integer()) {
    v = value.get<long long>();
  } else {
    // 16.0 is an integer written as a float; 16.5 is not.
    const double d = value.get<double>();
    if (!std::isfinite(d) || std::floor(d) != d)
      fail(path, "expected " + range + ", got the non-integer " + value.dump());
    if (d < static_cast<double>(lo) || d > static_cast<double>(hi))
      fail(path, "expected " + range + ", got " + value.dump());
    v = static_cast<long long>(d);
  }
  if (v < lo || v > hi) fail(path, "expected " + range + ", got " + value.dump());
  return v;
}

bool JsonReader::boolean(const Json& value, const std::string& path) const {
  if (!value.is_boolean()) fail(path, "expected true or false, got " + describe(value));
  return value.get<bool>();
}

std::string JsonReader::string(const Json& value, const std::string& path) const {
  if (!value.is_string()) fail(path, "expected a string, got " + describe(value));
  return value.get<std::string>();
}

glm::dvec3 JsonReader::vec3(const Json& value, const std::string& path) const {
  if (!value.is_array() || value.size() != 3)
    fail(path, "expected an array of 3 numbers, got " + describe(value));
  glm::dvec3 v;
  for (std::size_t i = 0; i < 3; ++i) {
    if (!value[i].is_number())
      fail(path, "expected an array of 3 numbers, element " + std::to_string(i) + " is " +
                     describe(value[i]));
    v[static_cast<glm::length_t>(i)] = number(value[i], join_index(path, i));
  }
  return v;
}

glm::vec3 JsonReader::vec3_f(const Json& value, const std::string& path) const {
  const glm::dvec3 v = vec3(value, path);
  for (glm::length_t i = 0; i < 3; ++i)
    if (std::abs(v[i]) > static_cast<double>(std::numeric_limits<float>::max()))
      fail(join_index(path, static_cast<std::size_t>(i)),
           "number is out of range for a 32-bit float");
  return glm::vec3(v);
}

}  // namespace bounce::scene_internal
