#pragma once
// A glTF file of one unit quad, written out for loader tests: the quad lies
// in z = 0 facing +z, with texture coordinates (x, 1 - y) as glTF's v runs
// down, its vertices, uvs and indices in a base64 buffer inside the JSON.
#include <cstdint>
#include <string>

namespace bounce::test {

inline std::string base64(const std::string& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const unsigned n = (static_cast<unsigned char>(in[i]) << 16) |
                       (static_cast<unsigned char>(in[i + 1]) << 8) |
                       static_cast<unsigned char>(in[i + 2]);
    out += {k[(n >> 18) & 63], k[(n >> 12) & 63], k[(n >> 6) & 63], k[n & 63]};
  }
  if (i + 1 == in.size()) {
    const unsigned n = static_cast<unsigned char>(in[i]) << 16;
    out += {k[(n >> 18) & 63], k[(n >> 12) & 63], '=', '='};
  } else if (i + 2 == in.size()) {
    const unsigned n =
        (static_cast<unsigned char>(in[i]) << 16) | (static_cast<unsigned char>(in[i + 1]) << 8);
    out += {k[(n >> 18) & 63], k[(n >> 12) & 63], k[(n >> 6) & 63], '='};
  }
  return out;
}

// The quad's .gltf text: its material's base colour texture is `image` (no
// texture and no coordinates when empty), texture 0; `material` is the
// material's JSON members after pbrMetallicRoughness (", \"alphaMode\": ...");
// `factor` its baseColorFactor.
inline std::string gltf_quad(const std::string& image, const std::string& material,
                             const std::string& factor) {
  std::string buffer;
  const auto put = [&](const auto& value) {
    buffer.append(reinterpret_cast<const char*>(&value), sizeof(value));
  };
  for (const float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f}) put(f);
  for (const float f : {0.f, 1.f, 1.f, 1.f, 1.f, 0.f, 0.f, 0.f}) put(f);
  for (const int i : {0, 1, 2, 0, 2, 3}) put(static_cast<std::uint16_t>(i));
  const bool textured = !image.empty();
  return
      R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0)" +
      std::string(textured ? R"(, "TEXCOORD_0": 1)" : "") +
      R"(}, "indices": 2, "material": 0}]}],
  "materials": [{"name": "leaf", "pbrMetallicRoughness": {"baseColorFactor": )" +
      factor + (textured ? R"(, "baseColorTexture": {"index": 0})" : "") + "}" + material + "}]," +
      (textured ? R"("textures": [{"source": 0}], "images": [{"uri": ")" + image + R"("}],)" : "") +
      R"(
  "buffers": [{"byteLength": 92, "uri": "data:application/octet-stream;base64,)" +
      base64(buffer) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                  {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
}

}  // namespace bounce::test
