#include "io/ply_writer.h"

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>

#include "base/error.h"
#include "io/atomic_file.h"
#include "io/tone_map.h"

namespace bounce {

namespace {

// Little-endian bytes whatever the host, so the header never lies.
void put_u32(std::vector<char>& out, std::uint32_t v) {
  for (int b = 0; b < 4; ++b) out.push_back(static_cast<char>((v >> (8 * b)) & 0xffu));
}
void put_f32(std::vector<char>& out, float v) { put_u32(out, std::bit_cast<std::uint32_t>(v)); }
void put_vec3(std::vector<char>& out, const glm::vec3& v) {
  for (int c = 0; c < 3; ++c) put_f32(out, v[c]);
}

}  // namespace

float write_lit_ply(const std::filesystem::path& path, const PlyMeshView& mesh,
                    const std::vector<PlyScalar>& scalars) {
  const std::size_t n = mesh.positions.size();
  if (mesh.normals.size() != n || mesh.radiance.size() != n)
    throw Error(path.string(), "PLY: positions, normals and radiance differ in count");
  for (const PlyScalar& s : scalars)
    if (!s.values || s.values->size() != n || s.name.empty() ||
        s.name.find_first_of(" \n") != std::string::npos)
      throw Error(path.string(), "PLY: vertex property '" + s.name +
                                     "' has no valid name or not one value per vertex");
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw Error(path.string(), "PLY: too many vertices for int indices");
  for (const glm::uvec3& t : mesh.triangles)
    for (int c = 0; c < 3; ++c)
      if (t[c] >= n) throw Error(path.string(), "PLY: a triangle names a vertex out of range");

  const float exposure = ToneMap::exposure_for(mesh.radiance);

  std::ostringstream header;
  header.precision(9);
  header << "ply\nformat binary_little_endian 1.0\n"
         << "comment Bounce: radiosity transferred from virtual patches to the mesh\n"
         << "comment red/green/blue: sRGB of radiance x exposure " << exposure
         << " (99th percentile of luminance -> 0.9); radiance_*: linear, exact\n"
         << "element vertex " << n << "\n"
         << "property float x\nproperty float y\nproperty float z\n"
         << "property float nx\nproperty float ny\nproperty float nz\n"
         << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
         << "property float radiance_r\nproperty float radiance_g\nproperty float radiance_b\n";
  for (const PlyScalar& s : scalars) header << "property float " << s.name << "\n";
  header << "element face " << mesh.triangles.size() << "\n"
         << "property list uchar int vertex_indices\nend_header\n";

  AtomicFile file(path);
  std::ostream& out = file.stream();
  const std::string h = header.str();
  out.write(h.data(), static_cast<std::streamsize>(h.size()));

  // Written in chunks: one buffer for a whole large mesh would double its memory.
  constexpr std::size_t kChunk = 1 << 16;
  std::vector<char> buf;
  buf.reserve(kChunk * 39);
  auto flush = [&] {
    out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
    buf.clear();
  };
  for (std::size_t v = 0; v < n; ++v) {
    put_vec3(buf, mesh.positions[v]);
    put_vec3(buf, mesh.normals[v]);
    for (int c = 0; c < 3; ++c)
      buf.push_back(static_cast<char>(ToneMap::srgb8(exposure * mesh.radiance[v][c])));
    put_vec3(buf, mesh.radiance[v]);
    for (const PlyScalar& s : scalars) put_f32(buf, (*s.values)[v]);
    if (buf.size() >= kChunk * 39) flush();
  }
  for (const glm::uvec3& t : mesh.triangles) {
    buf.push_back(3);
    for (int c = 0; c < 3; ++c) put_u32(buf, t[c]);
    if (buf.size() >= kChunk * 39) flush();
  }
  flush();
  file.commit();
  return exposure;
}

}  // namespace bounce
