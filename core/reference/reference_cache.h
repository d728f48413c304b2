#pragma once
// Converged references on disk, so a report (or the next bake) does not
// re-render them. The key is a 64-bit FNV-1a hash of everything the answer
// depends on: the scene as loaded (geometry, materials, sidedness, lights,
// camera -- which covers the content of scene.json and every mesh file it
// names, and also in-memory scenes), the path tracer's settings, and the
// query (image size, or the points). A changed light or setting is a
// different key, so a stale entry is never returned; entries are written to a
// temporary name and renamed (io/atomic_file.h), so a crash never leaves a
// half entry under a valid name.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "reference/path_tracer.h"
#include "scene/scene.h"

namespace bounce {

// FNV-1a over bytes: small, stable across runs and platforms of one
// endianness, good enough to tell scenes apart (not a security hash).
class ContentHash {
 public:
  ContentHash& bytes(const void* data, std::size_t size);
  ContentHash& text(const std::string& s);
  ContentHash& number(double v);
  ContentHash& integer(std::uint64_t v);
  ContentHash& vec(const glm::vec3& v);
  std::uint64_t value() const { return h_; }
  std::string hex() const;

 private:
  std::uint64_t h_ = 0xCBF29CE484222325ull;
};

// Hash of the scene content that light depends on, and of the settings.
void hash_scene(ContentHash& h, const Scene& scene);
void hash_settings(ContentHash& h, const ReferenceSettings& settings);

class ReferenceCache {
 public:
  explicit ReferenceCache(std::filesystem::path dir);
  // $XDG_CACHE_HOME/bounce/reference, else $HOME/.cache/bounce/reference.
  static std::filesystem::path default_dir();
  const std::filesystem::path& dir() const { return dir_; }

  // Floats stored under (kind, key); nullopt when absent or unreadable (a
  // truncated or foreign file is a miss, not an error).
  std::optional<std::vector<float>> load(const std::string& kind, std::uint64_t key) const;
  // Throws IoError when the folder or file cannot be written.
  void store(const std::string& kind, std::uint64_t key, const std::vector<float>& data) const;
  std::filesystem::path file_of(const std::string& kind, std::uint64_t key) const;

 private:
  std::filesystem::path dir_;
};

// Reference pictures of tracer's scene camera at `samples` paths per pixel
// (pt.settings().samples), from the cache when there, else rendered (in
// passes, so progress can cancel) and stored. `cache` may be null (no
// caching); `hit` (optional) says whether the cache answered.
ReferenceImages cached_reference_images(const ReferencePathTracer& pt, int width, int height,
                                        const ReferenceCache* cache, Progress* progress = nullptr,
                                        bool* hit = nullptr);

// The same for point estimates.
PointReference cached_reference_points(const ReferencePathTracer& pt,
                                       const std::vector<ReferencePoint>& points,
                                       const ReferenceCache* cache, Progress* progress = nullptr,
                                       bool* hit = nullptr);

}  // namespace bounce
