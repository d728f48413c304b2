#include "io/glb_writer.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include <nlohmann/json.hpp>

#include "base/error.h"
#include "io/atomic_file.h"
#include "io/tone_map.h"

namespace bounce {

namespace {

// glTF's numeric codes (component types, buffer-view targets, primitive mode).
constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kTriangles = 4;

// GLB container: a 12-byte header, then chunks of (length, type, data), each
// padded to 4 bytes ('JSON' with spaces, 'BIN\0' with zeros).
constexpr std::uint32_t kMagic = 0x46546C67u;  // "glTF"
constexpr std::uint32_t kVersion = 2;
constexpr std::uint32_t kChunkJson = 0x4E4F534Au;
constexpr std::uint32_t kChunkBin = 0x004E4942u;

// Little-endian bytes whatever the host.
void put_u32(std::string& out, std::uint32_t v) {
  for (int b = 0; b < 4; ++b) out.push_back(static_cast<char>((v >> (8 * b)) & 0xffu));
}
void put_vec3(std::string& out, const glm::vec3& v) {
  for (int c = 0; c < 3; ++c) put_u32(out, std::bit_cast<std::uint32_t>(v[c]));
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

float write_lit_glb(const std::filesystem::path& path, const GlbMeshView& mesh) {
  const std::string where = path.string();
  const std::size_t n = mesh.positions.size();
  if (mesh.normals.size() != n || mesh.radiance.size() != n)
    throw Error(where, "glTF: positions, normals and radiance differ in count");
  if (n == 0 || mesh.triangles.empty())
    throw Error(where, "glTF: the mesh has no vertices or no triangles to export");
  for (const glm::uvec3& t : mesh.triangles)
    for (int c = 0; c < 3; ++c)
      if (t[c] >= n) throw Error(where, "glTF: a triangle names a vertex out of range");
  for (std::size_t v = 0; v < n; ++v)
    if (!finite(mesh.positions[v]) || !finite(mesh.normals[v]) || !finite(mesh.radiance[v]))
      throw Error(where, "glTF: vertex " + std::to_string(v) + " has a NaN or infinite value");

  const float exposure = ToneMap::exposure_for(mesh.radiance);

  // Binary chunk: four per-vertex float VEC3 arrays, then the indices; every
  // view starts 4-byte aligned because each element is a multiple of 4 bytes.
  const std::size_t vec3_bytes = n * 12;
  const std::size_t index_bytes = mesh.triangles.size() * 12;
  const std::size_t bin_bytes = 4 * vec3_bytes + index_bytes;
  // Header, two chunk headers and the JSON (well under 4 KiB) must fit in
  // the container's 32-bit length too.
  if (bin_bytes > std::numeric_limits<std::uint32_t>::max() - (1u << 16))
    throw Error(where, "glTF: the mesh is too large for one .glb file (4 GiB limit)");

  std::string bin;
  bin.reserve(bin_bytes);
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (const glm::vec3& p : mesh.positions) {
    put_vec3(bin, p);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  for (const glm::vec3& nrm : mesh.normals) {
    // glTF requires unit normals; a zero normal (a degenerate corner) gets
    // any unit vector rather than making the file invalid.
    const float len = glm::length(nrm);
    put_vec3(bin, len > 0.0f ? nrm / len : glm::vec3(0.0f, 0.0f, 1.0f));
  }
  for (const glm::vec3& r : mesh.radiance)
    put_vec3(bin, glm::clamp(r * exposure, glm::vec3(0.0f), glm::vec3(1.0f)));
  for (const glm::vec3& r : mesh.radiance) put_vec3(bin, r);
  for (const glm::uvec3& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) put_u32(bin, t[c]);

  using nlohmann::json;
  json views = json::array(), accessors = json::array();
  auto add_vec3 = [&](std::size_t index, bool bounds) {
    views.push_back({{"buffer", 0},
                     {"byteOffset", index * vec3_bytes},
                     {"byteLength", vec3_bytes},
                     {"target", kArrayBuffer}});
    json a = {{"bufferView", index}, {"componentType", kFloat}, {"count", n}, {"type", "VEC3"}};
    // Viewers frame the model from POSITION's bounds, which glTF requires.
    if (bounds) {
      a["min"] = {lo.x, lo.y, lo.z};
      a["max"] = {hi.x, hi.y, hi.z};
    }
    accessors.push_back(std::move(a));
  };
  add_vec3(0, true);   // POSITION
  add_vec3(1, false);  // NORMAL
  add_vec3(2, false);  // COLOR_0
  add_vec3(3, false);  // _RADIANCE
  views.push_back({{"buffer", 0},
                   {"byteOffset", 4 * vec3_bytes},
                   {"byteLength", index_bytes},
                   {"target", kElementArrayBuffer}});
  accessors.push_back({{"bufferView", 4},
                       {"componentType", kUnsignedInt},
                       {"count", mesh.triangles.size() * 3},
                       {"type", "SCALAR"}});

  const json doc = {
      {"asset",
       {{"version", "2.0"},
        {"generator", "Bounce"},
        {"extras",
         {{"exposure", exposure},
          {"colours",
           "COLOR_0 = clamp(radiance x exposure, 0, 1), linear; _RADIANCE = "
           "radiance, linear, exact"}}}}},
      {"extensionsUsed", {"KHR_materials_unlit"}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}, {"name", mesh.name}}}},
      {"materials",
       {{{"name", "baked light"},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", {1.0, 1.0, 1.0, 1.0}},
           {"metallicFactor", 0.0},
           {"roughnessFactor", 1.0}}},
         {"extensions", {{"KHR_materials_unlit", json::object()}}}}}},
      {"meshes",
       {{{"name", mesh.name},
         {"primitives",
          {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"COLOR_0", 2}, {"_RADIANCE", 3}}},
            {"indices", 4},
            {"material", 0},
            {"mode", kTriangles}}}}}}},
      {"buffers", {{{"byteLength", bin_bytes}}}},
      {"bufferViews", views},
      {"accessors", accessors}};

  std::string text = doc.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  bin.append((4 - bin.size() % 4) % 4, '\0');

  std::string header;
  put_u32(header, kMagic);
  put_u32(header, kVersion);
  put_u32(header, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
  put_u32(header, static_cast<std::uint32_t>(text.size()));
  put_u32(header, kChunkJson);

  AtomicFile file(path);
  std::ostream& out = file.stream();
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  std::string bin_header;
  put_u32(bin_header, static_cast<std::uint32_t>(bin.size()));
  put_u32(bin_header, kChunkBin);
  out.write(bin_header.data(), static_cast<std::streamsize>(bin_header.size()));
  out.write(bin.data(), static_cast<std::streamsize>(bin.size()));
  file.commit();
  return exposure;
}

}  // namespace bounce
