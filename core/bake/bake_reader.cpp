#include "bake/bake_reader.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "bake/bake_writer.h"
#include "compress/dds.h"
#include "io/npy.h"

namespace bounce {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using ReadError = BakeReader::ReadError;

void require_shape(const fs::path& file, const std::vector<std::size_t>& shape,
                   const std::vector<std::size_t>& expected) {
  if (shape == expected) return;
  auto text = [](const std::vector<std::size_t>& s) {
    std::string t = "(";
    for (std::size_t k = 0; k < s.size(); ++k) t += (k ? ", " : "") + std::to_string(s[k]);
    return t + ")";
  };
  throw ReadError(file.string(), "has shape " + text(shape) + ", expected " + text(expected));
}

// The polygons each sample carries (carried_*.npy), when the bake has them
// (bakes before session 8 do not: their point lights are then evaluated at
// the samples). Only what the direct light reads comes back: the polygons and
// their areas, not the triangle parts they came from.
void read_carried_polygons(const fs::path& dir, SampleSet& samples) {
  const fs::path pf = dir / "carried_polygons.npy", af = dir / "carried_area.npy",
                 vf = dir / "carried_vertices.npy";
  if (!fs::exists(pf) && !fs::exists(af) && !fs::exists(vf)) return;
  const NpyArray<std::uint32_t> p = read_npy_u32(pf);
  if (p.shape.size() != 2 || p.shape[1] != 3) throw ReadError(pf.string(), "must have 3 columns");
  const std::size_t count = p.shape[0];
  const NpyArray<float> a = read_npy_f32(af);
  require_shape(af, a.shape, {count});
  const NpyArray<float> v = read_npy_f32(vf);
  if (v.shape.size() != 2 || v.shape[1] != 3) throw ReadError(vf.string(), "must have 3 columns");
  const std::size_t vertices = v.shape[0], sample_count = samples.samples.size();
  samples.carried_vertices.resize(vertices);
  for (std::size_t k = 0; k < vertices; ++k) {
    const glm::vec3 x(v.data[3 * k], v.data[3 * k + 1], v.data[3 * k + 2]);
    if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
      throw ReadError(vf.string(), "vertex " + std::to_string(k) + " is not finite");
    samples.carried_vertices[k] = x;
  }
  samples.carried.resize(count);
  samples.carried_first.assign(sample_count + 1, 0);
  std::uint32_t previous = 0;
  for (std::size_t c = 0; c < count; ++c) {
    const std::uint32_t sample = p.data[3 * c], first = p.data[3 * c + 1],
                        corners = p.data[3 * c + 2];
    const std::string polygon = "polygon " + std::to_string(c);
    if (sample >= sample_count || sample < previous)
      throw ReadError(pf.string(), polygon + " names sample " + std::to_string(sample) +
                                       " (samples: " + std::to_string(sample_count) +
                                       ", in order)");
    if (corners < 3 || first > vertices || corners > vertices - first)
      throw ReadError(pf.string(), polygon + " has vertices " + std::to_string(first) + " + " +
                                       std::to_string(corners) + " of " + std::to_string(vertices));
    if (!(a.data[c] >= 0.0f) || !std::isfinite(a.data[c]))
      throw ReadError(af.string(), polygon + " has area " + std::to_string(a.data[c]));
    previous = sample;
    samples.carried[c] = CarriedArea{
        std::numeric_limits<std::uint32_t>::max(), false, a.data[c], first, corners, false};
    ++samples.carried_first[sample + 1];
  }
  for (std::size_t k = 0; k < sample_count; ++k)
    samples.carried_first[k + 1] += samples.carried_first[k];
}

json read_manifest(const fs::path& dir) {
  const fs::path path = dir / "manifest.json";
  std::ifstream in(path);
  if (!in) throw ReadError(dir.string(), "is not a bake folder (no manifest.json)");
  json m;
  try {
    m = json::parse(in);
  } catch (const json::exception& e) {
    throw ReadError(path.string(), std::string("is not valid JSON: ") + e.what());
  }
  if (m.value("format", "") != "bounce-bake")
    throw ReadError(path.string(), "is not a Bounce bake manifest");
  const int version = m.value("format_version", 0);
  if (version != kBakeFormatVersion)
    throw ReadError(path.string(), "is bake format version " + std::to_string(version) +
                                       "; this bounce reads version " +
                                       std::to_string(kBakeFormatVersion) + " (bake again)");
  return m;
}

// Patches and their member samples from patches.npy and samples.npy.
void read_patches(const fs::path& dir, std::size_t n, LoadedBake& b) {
  const fs::path pf = dir / "patches.npy", sf = dir / "samples.npy";
  const NpyArray<float> p = read_npy_f32(pf);
  require_shape(pf, p.shape, {n, 15});
  const NpyArray<float> s = read_npy_f32(sf);
  if (s.shape.size() != 2 || s.shape[1] != 13) throw ReadError(sf.string(), "must have 13 columns");
  const std::size_t count = s.shape[0];
  for (std::size_t i = 0; i < n; ++i) {
    const float* r = &p.data[i * 15];
    Patch patch{};
    patch.position = {r[0], r[1], r[2]};
    patch.normal = {r[3], r[4], r[5]};
    patch.area = r[6];
    patch.albedo = {r[7], r[8], r[9]};
    patch.voxel = static_cast<std::uint32_t>(r[10]);
    patch.mesh = static_cast<std::uint32_t>(r[11]);
    patch.emission = {r[12], r[13], r[14]};
    b.patches.patches.push_back(patch);
  }
  std::vector<std::vector<std::uint32_t>> members(n);
  b.samples.samples.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    const float* r = &s.data[k * 13];
    Sample sample{};
    sample.position = {r[0], r[1], r[2]};
    sample.normal = {r[3], r[4], r[5]};
    sample.area = r[6];
    sample.albedo = {r[7], r[8], r[9]};
    sample.voxel = static_cast<std::uint32_t>(r[10]);
    sample.triangle = static_cast<std::uint32_t>(r[12]);
    b.samples.samples.push_back(sample);
    const float patch = r[11];
    if (patch < 0.0f) continue;  // its patch was left out
    if (patch >= static_cast<float>(n))
      throw ReadError(sf.string(), "sample " + std::to_string(k) + " names patch " +
                                       std::to_string(static_cast<long>(patch)) + " of " +
                                       std::to_string(n));
    members[static_cast<std::size_t>(patch)].push_back(static_cast<std::uint32_t>(k));
  }
  b.patches.member_first.push_back(0);
  for (const auto& m : members) {
    b.patches.member_samples.insert(b.patches.member_samples.end(), m.begin(), m.end());
    b.patches.member_first.push_back(static_cast<std::uint32_t>(b.patches.member_samples.size()));
  }
}

CompressedMatrix read_compressed(const fs::path& dir, const json& c, std::size_t n) {
  CompressedMatrix m;
  m.n = n;
  m.padded = c.at("padded_size").get<std::size_t>();
  m.channels = c.at("stored_channels").get<int>();
  m.codec = c.value("codec", "");
  m.encoder = c.value("encoder", "");
  m.ordering = c.value("ordering", "");
  m.kept_fraction = c.value("kept_fraction", 0.0);
  const DdsImage dds = read_dds(dir / "T.dds");
  if (dds.width != m.padded || dds.height != m.padded)
    throw ReadError((dir / "T.dds").string(),
                    "is " + std::to_string(dds.width) + " x " + std::to_string(dds.height) +
                        ", the manifest says " + std::to_string(m.padded));
  m.format = dds.format;
  m.blocks = dds.blocks;
  const fs::path pf = dir / "permutation.npy";
  NpyArray<std::uint32_t> perm = read_npy_u32(pf);
  require_shape(pf, perm.shape, {n});
  m.permutation = std::move(perm.data);
  if (!is_bijection(m.permutation))
    throw ReadError(pf.string(), "is not a permutation of 0.." + std::to_string(n - 1));
  for (const json& q : c.at("quantizers")) {
    LogQuantizer lq;
    lq.vmax = q.at("vmax").get<float>();
    lq.range = q.at("range").get<float>();
    m.quantizers.push_back(lq);
  }
  for (int ch = 0; ch < m.channels; ++ch) {
    const std::string base = "T_kept_" + std::to_string(ch);
    CsrMatrix k;
    k.n = n;
    const fs::path rp = dir / (base + "_row_ptr.npy"), cp = dir / (base + "_col.npy"),
                   vp = dir / (base + "_value.npy");
    k.row_ptr = read_npy_u32(rp).data;
    k.col = read_npy_u32(cp).data;
    k.value = read_npy_f32(vp).data;
    if (k.row_ptr.size() != n + 1 || k.row_ptr.back() != k.col.size() ||
        k.col.size() != k.value.size())
      throw ReadError(rp.string(), "CSR arrays of stored channel " + std::to_string(ch) +
                                       " do not fit together");
    for (std::size_t i = 0; i < n; ++i)
      if (k.row_ptr[i] > k.row_ptr[i + 1])
        throw ReadError(rp.string(), "row starts must not decrease");
    for (std::uint32_t col : k.col)
      if (col >= n) throw ReadError(cp.string(), "column index out of range");
    m.kept.push_back(std::move(k));
  }
  if (m.quantizers.size() != static_cast<std::size_t>(m.channels))
    throw ReadError((dir / "manifest.json").string(), "quantizer count differs from channels");
  return m;
}

}  // namespace

LoadedBake BakeReader::read(const fs::path& dir, bool with_dense) {
  // A manifest with missing or mistyped entries is a damaged bake: say so,
  // naming the file, rather than letting a JSON exception escape.
  try {
    return read_checked(dir, with_dense);
  } catch (const nlohmann::json::exception& e) {
    throw ReadError((dir / "manifest.json").string(),
                    std::string("lacks an entry or has one of the wrong type: ") + e.what());
  }
}

LoadedBake BakeReader::read_checked(const fs::path& dir, bool with_dense) {
  LoadedBake b;
  b.dir = dir;
  b.manifest = read_manifest(dir);
  const auto n = b.manifest.at("counts").at("patches").get<std::size_t>();
  read_patches(dir, n, b);
  read_carried_polygons(dir, b.samples);
  const json& t = b.manifest.at("transport");
  b.channel_of_rgb = t.at("channel_of_rgb").get<std::array<int, 3>>();
  b.stored_channels = static_cast<int>(t.at("channels").size());
  const json& c = b.manifest.at("compression");
  if (c.contains("stored_channels")) b.compressed = read_compressed(dir, c, n);
  const fs::path tf = dir / "T.npy";
  if (with_dense && fs::exists(tf)) {
    const NpyArray<float> dense = read_npy_f32(tf);
    const auto channels = static_cast<std::size_t>(b.stored_channels);
    require_shape(tf, dense.shape, {channels, n, n});
    for (std::size_t ch = 0; ch < channels; ++ch)
      b.dense.emplace_back(dense.data.begin() + static_cast<std::ptrdiff_t>(ch * n * n),
                           dense.data.begin() + static_cast<std::ptrdiff_t>((ch + 1) * n * n));
  }
  if (!b.compressed && b.dense.empty())
    throw ReadError(dir.string(), with_dense ? "holds no transport matrix (T.dds or T.npy)"
                                             : "holds no compressed transport matrix (T.dds)");
  const fs::path lf = dir / "lights_first_hit.npy";
  const NpyArray<float> lights = read_npy_f32(lf);
  if (lights.shape.size() != 3 || lights.shape[1] != n || lights.shape[2] != 3)
    throw ReadError(lf.string(), "must have shape (lights, " + std::to_string(n) + ", 3)");
  for (std::size_t l = 0; l < lights.shape[0]; ++l) {
    std::vector<glm::vec3> v(n);
    for (std::size_t p = 0; p < n; ++p) {
      const float* r = &lights.data[(l * n + p) * 3];
      v[p] = {r[0], r[1], r[2]};
    }
    b.probe.first_hit.push_back(std::move(v));
  }
  b.probe.channel_of_rgb = b.channel_of_rgb;
  for (const Patch& p : b.patches.patches) b.probe.area.push_back(p.area);
  return b;
}

}  // namespace bounce
