#include "scene/mtl_scan.h"

#include <fstream>
#include <string_view>

namespace bounce::scene_internal {

namespace {

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

// If `line` starts with the keyword `key` followed by whitespace, returns the
// rest of the line, trimmed (Assimp takes the whole rest as one name).
bool keyword(std::string_view line, std::string_view key, std::string_view& rest) {
  if (line.size() <= key.size() || line.substr(0, key.size()) != key) return false;
  const char after = line[key.size()];
  if (after != ' ' && after != '\t') return false;
  rest = trim(line.substr(key.size()));
  return true;
}

void scan_mtl(std::ifstream& in, MtlScan& scan) {
  std::string current;
  bool named = false;
  std::string line;
  std::string_view rest;
  while (std::getline(in, line)) {
    const std::string_view l = trim(line);
    if (keyword(l, "newmtl", rest)) {
      current = std::string(rest);
      named = true;
    } else if (named && (keyword(l, "Kd", rest) || keyword(l, "kd", rest)) && !rest.empty()) {
      scan.with_diffuse.insert(current);
    } else if (named && (keyword(l, "Ke", rest) || keyword(l, "ke", rest)) && !rest.empty()) {
      scan.with_emissive.insert(current);
    }
  }
}

}  // namespace

MtlScan scan_obj_materials(const std::filesystem::path& obj) {
  MtlScan scan;
  std::ifstream in(obj, std::ios::binary);
  std::string line;
  std::string_view rest;
  while (std::getline(in, line)) {
    if (!keyword(trim(line), "mtllib", rest) || rest.empty()) continue;
    std::filesystem::path file = obj.parent_path() / std::string(rest);
    std::ifstream mtl(file, std::ios::binary);
    if (!mtl) {
      // Assimp's fallback: the OBJ's own name with "mtl" for its extension.
      const std::string name = obj.string();
      file = name.substr(0, name.size() >= 3 ? name.size() - 3 : 0) + "mtl";
      mtl.open(file, std::ios::binary);
    }
    if (mtl) {
      scan_mtl(mtl, scan);
      scan.libraries.push_back(file);
    } else
      scan.missing_libraries.emplace_back(rest);
  }
  return scan;
}

}  // namespace bounce::scene_internal
