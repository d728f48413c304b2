#pragma once
// Typed, path-aware access to a parsed scene.json. Every value is read through
// a key path ("materials.leftWall.albedo", "lights[2].position") so that a
// wrong type or an absurd value fails with a LoadError naming the file and the
// exact key, and unknown or duplicate keys become warnings naming their path.
// Internal to the scene module (see docs/scene-format.md for the format).
#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "base/diagnostics.h"

namespace bounce::scene_internal {

using Json = nlohmann::json;

// 1-based line and column of a character in a text.
struct TextPosition {
  std::size_t line = 1;
  std::size_t column = 1;
};

// Position of the character at 0-based `index` (clamped to the text's end, so
// "unexpected end of input" points just past the last character).
TextPosition position_of_index(std::string_view text, std::size_t index);

// "member.key" / "key" when the parent is the root.
std::string join_key(const std::string& parent, std::string_view key);
// "parent[index]".
std::string join_index(const std::string& parent, std::size_t index);

class JsonReader {
 public:
  // `file` is what LoadErrors and warnings name as their `where`.
  JsonReader(std::string file, Diagnostics& diagnostics);

  // Parses `text`; a syntax error becomes "<file name>:<line>:<column>: <what>".
  // Duplicate keys are warned about (the last value wins, as in nlohmann).
  Json parse(const std::string& text) const;

  [[noreturn]] void fail(const std::string& key_path, const std::string& what) const;
  void warn(const std::string& key_path, const std::string& what) const;

  // Warns once for each key of `object` that is not in `known`.
  void warn_unknown_keys(const Json& object, const std::string& path,
                         std::initializer_list<std::string_view> known) const;

  void expect_object(const Json& value, const std::string& path) const;
  void expect_array(const Json& value, const std::string& path) const;
  // A finite number.
  double number(const Json& value, const std::string& path) const;
  float number_f(const Json& value, const std::string& path) const;
  // A number with an integral value in [lo, hi].
  long long integer(const Json& value, const std::string& path, long long lo, long long hi) const;
  bool boolean(const Json& value, const std::string& path) const;
  std::string string(const Json& value, const std::string& path) const;
  // An array of exactly 3 finite numbers.
  glm::dvec3 vec3(const Json& value, const std::string& path) const;
  glm::vec3 vec3_f(const Json& value, const std::string& path) const;

  // How a value looks, for messages: "a string (\"red\")", "an array of 2 elements".
  static std::string describe(const Json& value);

  const std::string& file() const { return file_; }

 private:
  std::string file_;
  Diagnostics& diagnostics_;
};

}  // namespace bounce::scene_internal
