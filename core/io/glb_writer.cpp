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

using nlohmann::json;

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
void put_float(std::string& out, float v) { put_u32(out, std::bit_cast<std::uint32_t>(v)); }

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(const glm::vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }

void check_primitive(const std::string& where, const GlbModel& model, std::size_t index) {
  const GlbPrimitive& p = model.primitives[index];
  const std::string which = "glTF: primitive " + std::to_string(index) + ": ";
  const std::size_t n = p.positions.size();
  if (p.normals.size() != n || p.light.size() != n || p.radiance.size() != n ||
      (!p.uv.empty() && p.uv.size() != n))
    throw Error(where, which + "positions, normals, texture coordinates and light differ in count");
  if (n == 0 || p.triangles.empty())
    throw Error(where, which + "the mesh has no vertices or no triangles to export");
  if (p.material >= model.materials.size())
    throw Error(where, which + "names a material out of range");
  for (const glm::uvec3& t : p.triangles)
    for (int c = 0; c < 3; ++c)
      if (t[c] >= n) throw Error(where, which + "a triangle names a vertex out of range");
  for (std::size_t v = 0; v < n; ++v)
    if (!finite(p.positions[v]) || !finite(p.normals[v]) || !finite(p.light[v]) ||
        !finite(p.radiance[v]) || (!p.uv.empty() && !finite(p.uv[v])))
      throw Error(where, which + "vertex " + std::to_string(v) + " has a NaN or infinite value");
}

// The binary chunk and the views and accessors into it, built side by side.
class BinaryChunk {
 public:
  // Appends one view of `bytes` (4-byte aligned) and returns its index.
  std::size_t add_view(std::string bytes, std::optional<int> target) {
    json view = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes.size()}};
    if (target) view["target"] = *target;
    bin_ += bytes;
    bin_.append((4 - bin_.size() % 4) % 4, '\0');
    views_.push_back(std::move(view));
    return views_.size() - 1;
  }
  template <typename Vec>
  std::size_t add_floats(const std::vector<Vec>& values, const char* type, bool bounds = false) {
    constexpr int kComponents = Vec::length();
    std::string bytes;
    bytes.reserve(values.size() * 4 * kComponents);
    Vec lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const Vec& v : values) {
      for (int c = 0; c < kComponents; ++c) put_float(bytes, v[c]);
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
    json a = {{"bufferView", add_view(std::move(bytes), kArrayBuffer)},
              {"componentType", kFloat},
              {"count", values.size()},
              {"type", type}};
    // Viewers frame the model from POSITION's bounds, which glTF requires.
    if (bounds) {
      a["min"] = json::array();
      a["max"] = json::array();
      for (int c = 0; c < kComponents; ++c) {
        a["min"].push_back(lo[c]);
        a["max"].push_back(hi[c]);
      }
    }
    accessors_.push_back(std::move(a));
    return accessors_.size() - 1;
  }
  std::size_t add_indices(const std::vector<glm::uvec3>& triangles) {
    std::string bytes;
    bytes.reserve(triangles.size() * 12);
    for (const glm::uvec3& t : triangles)
      for (int c = 0; c < 3; ++c) put_u32(bytes, t[c]);
    accessors_.push_back({{"bufferView", add_view(std::move(bytes), kElementArrayBuffer)},
                          {"componentType", kUnsignedInt},
                          {"count", triangles.size() * 3},
                          {"type", "SCALAR"}});
    return accessors_.size() - 1;
  }
  const std::string& bytes() const { return bin_; }
  const json& views() const { return views_; }
  const json& accessors() const { return accessors_; }

 private:
  std::string bin_;
  json views_ = json::array(), accessors_ = json::array();
};

json material_json(const GlbMaterial& m) {
  json pbr = {{"baseColorFactor", {m.base_color.r, m.base_color.g, m.base_color.b, m.base_color.a}},
              {"metallicFactor", 0.0},
              {"roughnessFactor", 1.0}};
  // Texture i samples image i (one texture per image, the default sampler:
  // linear filtering, repeat addressing, as the bake samples it).
  if (m.base_color_image) pbr["baseColorTexture"] = {{"index", *m.base_color_image}};
  json out = {{"name", m.name},
              {"pbrMetallicRoughness", pbr},
              {"extensions", {{"KHR_materials_unlit", json::object()}}}};
  if (m.alpha_cutoff) {
    out["alphaMode"] = "MASK";
    out["alphaCutoff"] = *m.alpha_cutoff;
  }
  return out;
}

}  // namespace

void write_glb(const std::filesystem::path& path, const GlbModel& model) {
  const std::string where = path.string();
  if (model.primitives.empty())
    throw Error(where, "glTF: the mesh has no vertices or no triangles to export");
  for (std::size_t p = 0; p < model.primitives.size(); ++p) check_primitive(where, model, p);
  if (!std::isfinite(model.exposure) || model.exposure < 0.0f)
    throw Error(where, "glTF: the exposure must be finite and not negative");
  for (const GlbMaterial& m : model.materials)
    if (m.base_color_image && *m.base_color_image >= model.images.size())
      throw Error(where, "glTF: material '" + m.name + "' names an image out of range");

  BinaryChunk bin;
  json primitives = json::array();
  for (const GlbPrimitive& p : model.primitives) {
    std::vector<glm::vec3> normals, colours;
    normals.reserve(p.normals.size());
    // glTF requires unit normals; a zero normal (a degenerate corner) gets
    // any unit vector rather than making the file invalid.
    for (const glm::vec3& nrm : p.normals) {
      const float len = glm::length(nrm);
      normals.push_back(len > 0.0f ? nrm / len : glm::vec3(0.0f, 0.0f, 1.0f));
    }
    colours.reserve(p.light.size());
    for (const glm::vec3& l : p.light)
      colours.push_back(glm::clamp(l * model.exposure, glm::vec3(0.0f), glm::vec3(1.0f)));
    json attributes = {{"POSITION", bin.add_floats(p.positions, "VEC3", true)},
                       {"NORMAL", bin.add_floats(normals, "VEC3")}};
    if (!p.uv.empty()) attributes["TEXCOORD_0"] = bin.add_floats(p.uv, "VEC2");
    attributes["COLOR_0"] = bin.add_floats(colours, "VEC3");
    attributes["_RADIANCE"] = bin.add_floats(p.radiance, "VEC3");
    primitives.push_back({{"attributes", attributes},
                          {"indices", bin.add_indices(p.triangles)},
                          {"material", p.material},
                          {"mode", kTriangles}});
  }
  json images = json::array(), textures = json::array(), materials = json::array();
  for (const GlbImage& image : model.images) {
    const std::size_t view =
        bin.add_view(std::string(image.bytes.begin(), image.bytes.end()), std::nullopt);
    images.push_back({{"name", image.name}, {"mimeType", image.mime_type}, {"bufferView", view}});
    textures.push_back({{"source", textures.size()}});
  }
  for (const GlbMaterial& m : model.materials) materials.push_back(material_json(m));

  // Header, two chunk headers and the JSON must fit in the container's
  // 32-bit length too.
  if (bin.bytes().size() > std::numeric_limits<std::uint32_t>::max() - (1u << 24))
    throw Error(where, "glTF: the mesh is too large for one .glb file (4 GiB limit)");

  json doc = {{"asset",
               {{"version", "2.0"},
                {"generator", "Bounce"},
                {"extras", {{"exposure", model.exposure}, {"colours", model.colours}}}}},
              {"extensionsUsed", {"KHR_materials_unlit"}},
              {"scene", 0},
              {"scenes", {{{"nodes", {0}}}}},
              {"nodes", {{{"mesh", 0}, {"name", model.name}}}},
              {"materials", materials},
              {"meshes", {{{"name", model.name}, {"primitives", primitives}}}},
              {"buffers", {{{"byteLength", bin.bytes().size()}}}},
              {"bufferViews", bin.views()},
              {"accessors", bin.accessors()}};
  if (!images.empty()) {
    doc["images"] = images;
    doc["textures"] = textures;
  }

  std::string text = doc.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  if (text.size() + bin.bytes().size() > std::numeric_limits<std::uint32_t>::max() - 28)
    throw Error(where, "glTF: the mesh is too large for one .glb file (4 GiB limit)");

  std::string header;
  put_u32(header, kMagic);
  put_u32(header, kVersion);
  put_u32(header, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.bytes().size()));
  put_u32(header, static_cast<std::uint32_t>(text.size()));
  put_u32(header, kChunkJson);

  AtomicFile file(path);
  std::ostream& out = file.stream();
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  std::string bin_header;
  put_u32(bin_header, static_cast<std::uint32_t>(bin.bytes().size()));
  put_u32(bin_header, kChunkBin);
  out.write(bin_header.data(), static_cast<std::streamsize>(bin_header.size()));
  out.write(bin.bytes().data(), static_cast<std::streamsize>(bin.bytes().size()));
  file.commit();
}

float write_lit_glb(const std::filesystem::path& path, const GlbMeshView& mesh) {
  const std::size_t n = mesh.positions.size();
  if (mesh.normals.size() != n || mesh.radiance.size() != n)
    throw Error(path.string(), "glTF: positions, normals and radiance differ in count");
  GlbModel model;
  model.name = mesh.name;
  model.exposure = ToneMap::exposure_for(mesh.radiance);
  model.colours =
      "COLOR_0 = clamp(radiance x exposure, 0, 1), linear; _RADIANCE = radiance, linear, exact";
  model.materials.push_back({"baked light", glm::vec4(1.0f), std::nullopt, std::nullopt});
  model.primitives.push_back(
      {0, mesh.positions, mesh.normals, {}, mesh.radiance, mesh.radiance, mesh.triangles});
  write_glb(path, model);
  return model.exposure;
}

}  // namespace bounce
