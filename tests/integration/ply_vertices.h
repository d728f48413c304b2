#pragma once
// The vertex block of a binary little-endian PLY written by `bounce solve`,
// read by hand (Assimp's PLY reader drops the float properties scripts use).
#include <algorithm>
#include <cstring>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_harness.h"

namespace bounce::itest {

// The vertex block of a binary little-endian PLY written by bounce:
// property names and one float row per vertex (colour bytes skipped).
struct PlyVertices {
  std::vector<std::string> names;  // float properties, in order
  std::vector<std::vector<float>> rows;
  std::size_t column(const std::string& name) const {
    const auto it = std::find(names.begin(), names.end(), name);
    EXPECT_NE(it, names.end()) << name;
    return static_cast<std::size_t>(it - names.begin());
  }
};

inline PlyVertices read_ply_vertices(const fs::path& path) {
  const std::string text = read_text(path);
  const std::size_t end = text.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  std::istringstream header(text.substr(0, end));
  std::string line;
  std::size_t count = 0;
  bool in_vertex = false;
  std::vector<std::pair<std::string, bool>> properties;  // name, is float
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string word, type, name;
    words >> word;
    if (word == "element") {
      words >> name;
      in_vertex = name == "vertex";
      if (in_vertex) words >> count;
    } else if (word == "property" && in_vertex) {
      words >> type >> name;
      properties.emplace_back(name, type == "float");
    }
  }
  PlyVertices v;
  for (const auto& [name, is_float] : properties)
    if (is_float) v.names.push_back(name);
  const char* p = text.data() + end + std::strlen("end_header\n");
  for (std::size_t i = 0; i < count; ++i) {
    std::vector<float> row;
    for (const auto& [name, is_float] : properties) {
      if (is_float) {
        float f = 0.0f;
        std::memcpy(&f, p, 4);
        row.push_back(f);
        p += 4;
      } else {
        p += 1;  // uchar colour
      }
    }
    v.rows.push_back(std::move(row));
  }
  return v;
}

}  // namespace bounce::itest
