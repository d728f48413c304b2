#include "reference/reference_cache.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "io/atomic_file.h"
#include "io/cache_dir.h"
#include "scene/alpha_mask.h"
#include "scene/texture.h"

namespace bounce {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'B', 'N', 'C', 'R', 'E', 'F', '0', '1'};

void append(std::vector<float>& out, const std::vector<glm::vec3>& v) {
  for (const glm::vec3& x : v) out.insert(out.end(), {x.r, x.g, x.b});
}

// Reads `count` vec3 from data at `at`; false when data is too short.
bool take(const std::vector<float>& data, std::size_t& at, std::size_t count,
          std::vector<glm::vec3>& v) {
  if (data.size() < at + 3 * count) return false;
  v.resize(count);
  for (std::size_t i = 0; i < count; ++i, at += 3) v[i] = {data[at], data[at + 1], data[at + 2]};
  return true;
}

}  // namespace

ContentHash& ContentHash::bytes(const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    h_ ^= p[i];
    h_ *= 0x100000001B3ull;
  }
  return *this;
}

ContentHash& ContentHash::text(const std::string& s) {
  integer(s.size());
  return bytes(s.data(), s.size());
}

ContentHash& ContentHash::number(double v) { return bytes(&v, sizeof v); }
ContentHash& ContentHash::integer(std::uint64_t v) { return bytes(&v, sizeof v); }
ContentHash& ContentHash::vec(const glm::vec3& v) { return bytes(&v, sizeof v); }

std::string ContentHash::hex() const {
  char s[17];
  std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(h_));
  return s;
}

namespace {

// A texture's factor, size and full-resolution texels.
void hash_texture(ContentHash& h, const Texture& texture, const glm::vec3& factor) {
  const Texture::Level& l = texture.levels.front();
  h.vec(factor)
      .integer(static_cast<std::uint64_t>(l.width))
      .integer(static_cast<std::uint64_t>(l.height));
  h.bytes(l.texels.data(), l.texels.size() * sizeof(glm::vec3));
}

}  // namespace

void hash_scene(ContentHash& h, const Scene& scene) {
  h.integer(scene.positions.size())
      .bytes(scene.positions.data(), scene.positions.size() * sizeof(glm::vec3));
  h.integer(scene.triangles.size())
      .bytes(scene.triangles.data(), scene.triangles.size() * sizeof(glm::uvec3));
  h.bytes(scene.triangle_material.data(), scene.triangle_material.size() * sizeof(std::uint32_t));
  h.bytes(scene.triangle_mesh.data(), scene.triangle_mesh.size() * sizeof(std::uint32_t));
  h.integer(scene.materials.size());
  for (const Material& m : scene.materials) {
    h.vec(m.albedo).vec(m.emission);
    // The texels themselves: a texture edited in place must not reuse a result.
    if (m.texture) hash_texture(h, *m.texture, m.texture_factor);
    // Likewise the mask, only when there is one, so that results cached
    // for a scene without masks stay valid.
    if (m.alpha_mask) {
      const AlphaMask& a = *m.alpha_mask;
      h.integer(static_cast<std::uint64_t>(a.width)).integer(static_cast<std::uint64_t>(a.height));
      h.bytes(a.values.data(), a.values.size() * sizeof(float));
      h.bytes(&m.alpha_factor, sizeof(float)).bytes(&m.alpha_cutoff, sizeof(float));
    }
    // Likewise the emissive texture. Normal maps change no reference result
    // (only the preview draws them), so they are not part of the key.
    if (m.emission_texture) hash_texture(h, *m.emission_texture, m.emission_factor);
  }
  h.integer(scene.triangle_uv.size())
      .bytes(scene.triangle_uv.data(), scene.triangle_uv.size() * sizeof(scene.triangle_uv[0]));
  // Vertex colours only when there are some, so that results cached for a
  // scene without them stay valid.
  if (scene.has_vertex_colours())
    h.integer(scene.triangle_colour.size())
        .bytes(scene.triangle_colour.data(),
               scene.triangle_colour.size() * sizeof(scene.triangle_colour[0]));
  h.integer(scene.meshes.size());
  for (const MeshInfo& m : scene.meshes)
    h.integer(m.first_triangle).integer(m.triangle_count).integer(m.two_sided ? 1 : 0);
  h.integer(scene.lights.size());
  for (const Light& l : scene.lights)
    h.integer(static_cast<std::uint64_t>(l.type))
        .vec(l.position)
        .vec(l.direction)
        .vec(l.color)
        .number(l.intensity)
        .number(l.spot_inner_deg)
        .number(l.spot_outer_deg);
  h.vec(scene.camera.position).vec(scene.camera.target).vec(scene.camera.up);
  h.number(scene.camera.fov_y_deg);
}

void hash_settings(ContentHash& h, const ReferenceSettings& s) {
  // Not the thread count: results do not depend on it. The estimator's
  // version is: a changed estimator must not reuse answers cached by an older
  // one (2: MIS between NEE and bounce-ray emission, edge-point origins).
  constexpr std::uint64_t kEstimatorVersion = 2;
  h.integer(kEstimatorVersion);
  h.integer(static_cast<std::uint64_t>(s.samples))
      .integer(static_cast<std::uint64_t>(s.min_bounces))
      .integer(static_cast<std::uint64_t>(s.max_bounces))
      .integer(s.seed);
}

ReferenceCache::ReferenceCache(fs::path dir) : dir_(std::move(dir)) {}

fs::path ReferenceCache::default_dir() { return user_cache_dir("reference"); }

fs::path ReferenceCache::file_of(const std::string& kind, std::uint64_t key) const {
  char name[17];
  std::snprintf(name, sizeof name, "%016llx", static_cast<unsigned long long>(key));
  return dir_ / (kind + "-" + name + ".bin");
}

std::optional<std::vector<float>> ReferenceCache::load(const std::string& kind,
                                                       std::uint64_t key) const {
  std::ifstream in(file_of(kind, key), std::ios::binary);
  if (!in) return std::nullopt;
  char magic[8];
  std::uint64_t stored_key = 0, count = 0;
  in.read(magic, sizeof magic);
  in.read(reinterpret_cast<char*>(&stored_key), sizeof stored_key);
  in.read(reinterpret_cast<char*>(&count), sizeof count);
  if (!in || std::memcmp(magic, kMagic, sizeof magic) != 0 || stored_key != key ||
      count > (std::uint64_t{1} << 34))
    return std::nullopt;
  std::vector<float> data(count);
  in.read(reinterpret_cast<char*>(data.data()),
          static_cast<std::streamsize>(count * sizeof(float)));
  if (!in) return std::nullopt;
  return data;
}

void ReferenceCache::store(const std::string& kind, std::uint64_t key,
                           const std::vector<float>& data) const {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw IoError(dir_.string(), "cannot create the reference cache folder: " + ec.message());
  AtomicFile file(file_of(kind, key));
  const std::uint64_t count = data.size();
  file.stream().write(kMagic, sizeof kMagic);
  file.stream().write(reinterpret_cast<const char*>(&key), sizeof key);
  file.stream().write(reinterpret_cast<const char*>(&count), sizeof count);
  file.stream().write(reinterpret_cast<const char*>(data.data()),
                      static_cast<std::streamsize>(count * sizeof(float)));
  file.commit();
}

ReferenceImages cached_reference_images(const ReferencePathTracer& pt, int width, int height,
                                        const ReferenceCache* cache, Progress* progress,
                                        bool* hit) {
  ContentHash h;
  h.text("images");
  hash_scene(h, pt.tracer().scene());
  hash_settings(h, pt.settings());
  h.integer(static_cast<std::uint64_t>(width)).integer(static_cast<std::uint64_t>(height));
  const std::uint64_t key = h.value();
  const auto pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (hit) *hit = false;
  if (cache) {
    if (auto data = cache->load("images", key); data && data->size() == 1 + 13 * pixels) {
      ReferenceImages out;
      out.samples = static_cast<int>((*data)[0]);
      std::size_t at = 1;
      out.full = out.indirect = out.full_variance = out.indirect_variance =
          RgbFloatImage(width, height);
      take(*data, at, pixels, out.full.pixels);
      take(*data, at, pixels, out.indirect.pixels);
      take(*data, at, pixels, out.full_variance.pixels);
      take(*data, at, pixels, out.indirect_variance.pixels);
      out.coverage.assign(data->begin() + static_cast<std::ptrdiff_t>(at), data->end());
      if (hit) *hit = true;
      return out;
    }
  }
  ReferenceRenderer renderer(pt, width, height);
  // Passes of 16 paths: progress and cancellation between them.
  const int total = pt.settings().samples;
  while (renderer.samples() < total)
    renderer.add_samples(std::min(16, total - renderer.samples()), progress);
  ReferenceImages out = renderer.images();
  if (cache) {
    std::vector<float> data{static_cast<float>(out.samples)};
    data.reserve(1 + 13 * pixels);
    append(data, out.full.pixels);
    append(data, out.indirect.pixels);
    append(data, out.full_variance.pixels);
    append(data, out.indirect_variance.pixels);
    data.insert(data.end(), out.coverage.begin(), out.coverage.end());
    cache->store("images", key, data);
  }
  return out;
}

PointReference cached_reference_points(const ReferencePathTracer& pt,
                                       const std::vector<ReferencePoint>& points,
                                       const ReferenceCache* cache, Progress* progress, bool* hit) {
  ContentHash h;
  h.text("points");
  hash_scene(h, pt.tracer().scene());
  hash_settings(h, pt.settings());
  h.integer(points.size());
  for (const ReferencePoint& p : points)
    h.vec(p.position).vec(p.normal).vec(p.albedo).vec(p.emission);
  const std::uint64_t key = h.value();
  const std::size_t n = points.size();
  if (hit) *hit = false;
  if (cache) {
    if (auto data = cache->load("points", key); data && data->size() == 1 + 15 * n) {
      PointReference out;
      out.samples = static_cast<int>((*data)[0]);
      std::size_t at = 1;
      take(*data, at, n, out.direct_irradiance);
      take(*data, at, n, out.indirect_irradiance);
      take(*data, at, n, out.indirect_variance);
      take(*data, at, n, out.radiosity);
      take(*data, at, n, out.radiosity_variance);
      if (hit) *hit = true;
      return out;
    }
  }
  PointReference out = pt.estimate_points(points, progress);
  if (cache) {
    std::vector<float> data{static_cast<float>(out.samples)};
    data.reserve(1 + 15 * n);
    append(data, out.direct_irradiance);
    append(data, out.indirect_irradiance);
    append(data, out.indirect_variance);
    append(data, out.radiosity);
    append(data, out.radiosity_variance);
    cache->store("points", key, data);
  }
  return out;
}

}  // namespace bounce
