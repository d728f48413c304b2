#include "bake/bake_key.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <string_view>

#include "bake/rebake_plan.h"
#include "folder/bake_format.h"
#include "folder/bake_reader.h"
#include "reference/reference_cache.h"
#include "scene/scene_files.h"
#include "settings/settings_table.h"

namespace bounce {

namespace fs = std::filesystem;

namespace {

// Raised when the key's recipe changes, so older keys never match.
constexpr std::uint64_t kKeyVersion = 1;

// Where the matrices live while baking, not what the bake holds (the same
// result either way), and a path: not part of the key.
constexpr std::array<std::string_view, 2> kNotInKey = {"out_of_core", "out_of_core_dir"};

// The file's size and bytes; false when it cannot be read whole.
bool hash_file(ContentHash& h, const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) return false;
  h.integer(size);
  std::array<char, 1 << 16> buffer;
  std::uintmax_t total = 0;
  while (in) {
    in.read(buffer.data(), buffer.size());
    const auto got = static_cast<std::size_t>(in.gcount());
    h.bytes(buffer.data(), got);
    total += got;
  }
  return total == size;
}

// A setting's canonical text: the row's text, but doubles to full precision
// (the row's text rounds to 6 digits, which would let 0.02 and 0.0200001
// share a key).
std::string canonical_text(const SettingRow& row, const SettingValue& value) {
  if (const double* d = std::get_if<double>(&value)) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", *d);
    return text;
  }
  return setting_text(row, value);
}

void hash_bake_settings(ContentHash& h, const Scene& scene, const BakeSettings& settings) {
  BakeSettings s = settings;
  s.apply_scene_defaults(scene.defaults);
  for (const SettingRow& row : settings_table()) {
    const std::string_view name = row.name;
    if (std::find(kNotInKey.begin(), kNotInKey.end(), name) != kNotInKey.end()) continue;
    h.text(row.name).text(canonical_text(row, row.get(s)));
  }
  // Not table rows, but they decide the transport too (as in plan_rebake).
  h.number(s.transport.auto_tolerance)
      .integer(static_cast<std::uint64_t>(s.transport.max_auto_bounces));
}

}  // namespace

std::optional<std::string> scene_content_hash(const Scene& scene) {
  const std::vector<fs::path> files = scene_source_files(scene);
  if (files.empty()) return std::nullopt;
  ContentHash h;
  h.integer(files.size());
  for (const fs::path& file : files)
    if (!hash_file(h, file)) return std::nullopt;
  return h.hex();
}

std::string bake_key(const std::string& content, const Scene& scene, const BakeSettings& settings) {
  ContentHash h;
  h.text(kBakeFormatName).integer(kKeyVersion).integer(kBakeFormatVersion);
  h.text(content);
  const std::vector<float> densities = patch_densities(scene);
  h.integer(densities.size()).bytes(densities.data(), densities.size() * sizeof(float));
  hash_bake_settings(h, scene, settings);
  return h.hex();
}

std::optional<std::string> bake_key(const Scene& scene, const BakeSettings& settings) {
  const std::optional<std::string> content = scene_content_hash(scene);
  if (!content) return std::nullopt;
  return bake_key(*content, scene, settings);
}

std::optional<std::string> stored_bake_key(const fs::path& dir, std::string* why) {
  std::string reason;
  std::optional<std::string> key;
  const fs::path manifest = dir / bake_file::kManifest;
  std::error_code ec;
  if (fs::exists(manifest, ec)) {
    try {
      const nlohmann::json m = read_manifest_json(manifest);
      const auto k = m.find("key");
      if (k == m.end() || !k->is_string())
        throw BakeReader::ReadError(manifest.string(), "has no content key (an older bake)");
      // Every file the manifest lists, at the size it was written with: a
      // folder a crash or a user left half-copied is not a bake to reuse.
      for (const nlohmann::json& f : m.at("files")) {
        const fs::path file = dir / f.at("name").get<std::string>();
        const std::uintmax_t bytes = fs::file_size(file, ec);
        if (ec || bytes != f.at("bytes").get<std::uintmax_t>())
          throw BakeReader::ReadError(file.string(), "missing or not the size the manifest says");
      }
      BakeReader::read(dir, BakeReader::Dense::kIfNotCompressed);
      key = k->get<std::string>();
    } catch (const std::exception& e) {
      reason = e.what();
    }
  }
  if (why) *why = reason;
  return key;
}

}  // namespace bounce
