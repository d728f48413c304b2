#include "folder/bake_reader.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <string>

#include "base/checked_size.h"
#include "compress/dds.h"
#include "folder/bake_format.h"
#include "io/npy.h"
#include "runtime/seen_first_hit.h"
#include "voxel/voxel_grid.h"

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
// (older bakes without carried_*.npy do not: their point lights are then evaluated at
// the samples). Only what the direct light reads comes back: the polygons and
// their areas and the triangle and side each lies on, not the voxelization's
// triangle parts they came from.
void read_carried_polygons(const fs::path& dir, SampleSet& samples) {
  const fs::path pf = dir / bake_file::kCarriedPolygons, af = dir / bake_file::kCarriedArea,
                 vf = dir / bake_file::kCarriedVertices;
  if (!fs::exists(pf) && !fs::exists(af) && !fs::exists(vf)) return;
  const NpyArray<std::uint32_t> p = read_npy_u32(pf);
  namespace cc = carried_polygon_column;
  if (p.shape.size() != 2 || (p.shape[1] != cc::kCount && p.shape[1] != cc::kCountWithoutTriangles))
    throw ReadError(pf.string(), "must have " + std::to_string(cc::kCount) + " columns (or " +
                                     std::to_string(cc::kCountWithoutTriangles) +
                                     ", from older bakes)");
  const std::size_t columns = p.shape[1];
  const bool triangles = columns == cc::kCount;
  const std::size_t count = p.shape[0];
  const NpyArray<float> a = read_npy_f32(af);
  require_shape(af, a.shape, {count});
  const NpyArray<float> v = read_npy_f32(vf);
  if (v.shape.size() != 2 || v.shape[1] != kBakeVectorComponents)
    throw ReadError(vf.string(), "must have " + std::to_string(kBakeVectorComponents) + " columns");
  const std::size_t vertices = v.shape[0], sample_count = samples.samples.size();
  samples.carried_vertices.resize(vertices);
  for (std::size_t k = 0; k < vertices; ++k) {
    const float* r = &v.data[kBakeVectorComponents * k];
    const glm::vec3 x(r[0], r[1], r[2]);
    if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
      throw ReadError(vf.string(), "vertex " + std::to_string(k) + " is not finite");
    samples.carried_vertices[k] = x;
  }
  samples.carried.resize(count);
  samples.carried_first.assign(sample_count + 1, 0);
  std::uint32_t previous = 0;
  for (std::size_t c = 0; c < count; ++c) {
    const std::uint32_t* row = &p.data[columns * c];
    const std::uint32_t sample = row[carried_polygon_column::kSample],
                        first = row[carried_polygon_column::kFirstVertex],
                        corners = row[carried_polygon_column::kVertexCount],
                        triangle = triangles ? row[cc::kTriangle] : CarriedArea::kUnknownTriangle,
                        back = triangles ? row[cc::kBack] : 0;
    const std::string polygon = "polygon " + std::to_string(c);
    if (sample >= sample_count || sample < previous)
      throw ReadError(pf.string(), polygon + " names sample " + std::to_string(sample) +
                                       " (samples: " + std::to_string(sample_count) +
                                       ", in order)");
    if (corners < 3 || first > vertices || corners > vertices - first)
      throw ReadError(pf.string(), polygon + " has vertices " + std::to_string(first) + " + " +
                                       std::to_string(corners) + " of " + std::to_string(vertices));
    if (back > 1)
      throw ReadError(pf.string(), polygon + " has side " + std::to_string(back) + " (0 or 1)");
    if (!(a.data[c] >= 0.0f) || !std::isfinite(a.data[c]))
      throw ReadError(af.string(), polygon + " has area " + std::to_string(a.data[c]));
    previous = sample;
    samples.carried[c] = CarriedArea{std::numeric_limits<std::uint32_t>::max(),
                                     back == 1,
                                     a.data[c],
                                     first,
                                     corners,
                                     false,
                                     triangle};
    ++samples.carried_first[sample + 1];
  }
  for (std::size_t k = 0; k < sample_count; ++k)
    samples.carried_first[k + 1] += samples.carried_first[k];
}

json read_manifest(const fs::path& dir) {
  const fs::path path = dir / bake_file::kManifest;
  if (!fs::exists(path)) throw ReadError(dir.string(), "is not a bake folder (no manifest.json)");
  json m = read_manifest_json(path);
  if (!m.is_object() || m.value("format", "") != kBakeFormatName)
    throw ReadError(path.string(), "is not a Bounce bake manifest");
  const int version = m.value("format_version", 0);
  if (version != kBakeFormatVersion)
    throw ReadError(path.string(), "is bake format version " + std::to_string(version) +
                                       "; this bounce reads version " +
                                       std::to_string(kBakeFormatVersion) + " (bake again)");
  return m;
}

// Every value of a (rows, columns) float array is finite: positions,
// normals and areas feed rays and sums that would otherwise turn NaN far
// from the file that caused it.
void require_finite(const fs::path& file, const NpyArray<float>& a) {
  const std::size_t columns = a.shape.size() == 2 ? a.shape[1] : 1;
  for (std::size_t k = 0; k < a.data.size(); ++k)
    if (!std::isfinite(a.data[k]))
      throw ReadError(file.string(), "row " + std::to_string(k / columns) + ", column " +
                                         std::to_string(k % columns) + " is not finite");
}

// An index stored as a float column (voxel, mesh, triangle): a whole number
// that fits in 32 bits. Converting anything else to an integer is undefined.
std::uint32_t index_column(const fs::path& file, std::size_t row, std::size_t column, float v) {
  if (!(v >= 0.0f && v <= 4294967040.0f && v == std::floor(v)))
    throw ReadError(file.string(), "row " + std::to_string(row) + ", column " +
                                       std::to_string(column) + " holds " + std::to_string(v) +
                                       ", not an index");
  return static_cast<std::uint32_t>(v);
}

// Patches and their member samples from patches.npy and samples.npy.
void read_patches(const fs::path& dir, std::size_t n, LoadedBake& b) {
  namespace pc = patch_column;
  namespace sc = sample_column;
  const fs::path pf = dir / bake_file::kPatches, sf = dir / bake_file::kSamples;
  const NpyArray<float> p = read_npy_f32(pf);
  require_shape(pf, p.shape, {n, pc::kCount});
  require_finite(pf, p);
  const NpyArray<float> s = read_npy_f32(sf);
  if (s.shape.size() != 2 || s.shape[1] != sc::kCount)
    throw ReadError(sf.string(), "must have " + std::to_string(sc::kCount) + " columns");
  require_finite(sf, s);
  const std::size_t count = s.shape[0];
  if (count > std::numeric_limits<std::uint32_t>::max())
    throw ReadError(sf.string(), "has " + std::to_string(count) + " samples, more than 2^32 - 1");
  const auto vec3_at = [](const float* r, std::size_t c) {
    return glm::vec3(r[c], r[c + 1], r[c + 2]);
  };
  for (std::size_t i = 0; i < n; ++i) {
    const float* r = &p.data[i * pc::kCount];
    Patch patch{};
    patch.position = vec3_at(r, pc::kPosition);
    patch.normal = vec3_at(r, pc::kNormal);
    patch.area = r[pc::kArea];
    patch.albedo = vec3_at(r, pc::kAlbedo);
    patch.voxel = index_column(pf, i, pc::kVoxel, r[pc::kVoxel]);
    patch.mesh = index_column(pf, i, pc::kMesh, r[pc::kMesh]);
    patch.emission = vec3_at(r, pc::kEmission);
    b.patches.patches.push_back(patch);
  }
  std::vector<std::vector<std::uint32_t>> members(n);
  b.samples.samples.reserve(count);
  b.patch_of_sample.assign(count, -1);
  for (std::size_t k = 0; k < count; ++k) {
    const float* r = &s.data[k * sc::kCount];
    Sample sample{};
    sample.position = vec3_at(r, sc::kPosition);
    sample.normal = vec3_at(r, sc::kNormal);
    sample.area = r[sc::kArea];
    sample.albedo = vec3_at(r, sc::kAlbedo);
    sample.voxel = index_column(sf, k, sc::kVoxel, r[sc::kVoxel]);
    sample.triangle = index_column(sf, k, sc::kTriangle, r[sc::kTriangle]);
    b.samples.samples.push_back(sample);
    const float patch = r[sc::kPatch];
    if (patch < 0.0f) continue;  // its patch was left out
    if (patch >= static_cast<float>(n) || patch != std::floor(patch))
      throw ReadError(sf.string(), "sample " + std::to_string(k) + " names patch " +
                                       std::to_string(patch) + " of " + std::to_string(n));
    members[static_cast<std::size_t>(patch)].push_back(static_cast<std::uint32_t>(k));
    b.patch_of_sample[k] = static_cast<std::int32_t>(patch);
  }
  b.patches.member_first.push_back(0);
  for (const auto& m : members) {
    b.patches.member_samples.insert(b.patches.member_samples.end(), m.begin(), m.end());
    b.patches.member_first.push_back(static_cast<std::uint32_t>(b.patches.member_samples.size()));
  }
}

// The seen weights of the bake's final gather (runtime/seen_first_hit.h):
// a patch's first-hit light is then its samples' as the gather's rays see
// them. Bakes made before them have none and use area means.
void read_seen_weights(const fs::path& dir, LoadedBake& b) {
  const fs::path ff = dir / bake_file::kGatherSeenFirst;
  std::error_code ec;
  if (!fs::exists(ff, ec)) return;
  const fs::path sf = dir / bake_file::kGatherSeenSample, wf = dir / bake_file::kGatherSeenWeight;
  const NpyArray<std::uint32_t> first = read_npy_u32(ff);
  require_shape(ff, first.shape, {b.patches.size() + 1});
  const NpyArray<std::uint32_t> sample = read_npy_u32(sf);
  if (sample.shape.size() != 1) throw ReadError(sf.string(), "expected a one-dimensional array");
  const NpyArray<float> weight = read_npy_f32(wf);
  require_shape(wf, weight.shape, {sample.shape[0]});
  FinalGather g;
  g.patches = b.patches.size();
  g.seen_first = first.data;
  g.seen_sample = sample.data;
  g.seen_weight = weight.data;
  try {
    set_seen_weights(g, b.patches, "");
  } catch (const Error& e) {
    throw ReadError(ff.string(), e.what());
  }
}

// The cells of voxels.npy, checked against the samples that name them
// (none when a folder lacks the file: the bake still relights).
void read_voxel_cells(const fs::path& dir, LoadedBake& b) {
  namespace vc = voxel_column;
  const fs::path vf = dir / bake_file::kVoxels;
  std::error_code ec;
  if (!fs::exists(vf, ec)) return;
  const NpyArray<float> v = read_npy_f32(vf);
  if (v.shape.size() != 2 || v.shape[1] != vc::kCount)
    throw ReadError(vf.string(), "must have " + std::to_string(vc::kCount) + " columns");
  const std::size_t count = v.shape[0];
  b.voxel_cells.resize(count);
  for (std::size_t k = 0; k < count; ++k)
    for (int c = 0; c < 3; ++c) {
      const std::size_t column = vc::kCell + static_cast<std::size_t>(c);
      const std::uint32_t i = index_column(vf, k, column, v.data[k * vc::kCount + column]);
      if (i > static_cast<std::uint32_t>(VoxelGrid::kMaxResolution))
        throw ReadError(vf.string(), "voxel " + std::to_string(k) + " has cell index " +
                                         std::to_string(i) + ", beyond any grid");
      b.voxel_cells[k][c] = static_cast<int>(i);
    }
  for (std::size_t s = 0; s < b.samples.samples.size(); ++s)
    if (b.samples.samples[s].voxel >= count)
      throw ReadError((dir / bake_file::kSamples).string(),
                      "sample " + std::to_string(s) + " names voxel " +
                          std::to_string(b.samples.samples[s].voxel) + " of " +
                          std::to_string(count));
}

// A one-dimensional array of `expected` elements (any, when nullopt).
template <typename T>
std::vector<T> read_vector(const fs::path& file, NpyArray<T> (*read)(const fs::path&),
                           std::optional<std::size_t> expected) {
  NpyArray<T> a = read(file);
  if (a.shape.size() != 1)
    throw ReadError(file.string(), "must be one-dimensional, has " +
                                       std::to_string(a.shape.size()) + " dimensions");
  if (expected && a.shape[0] != *expected)
    throw ReadError(file.string(), "has " + std::to_string(a.shape[0]) + " elements, expected " +
                                       std::to_string(*expected));
  return std::move(a.data);
}

// The kept entries of stored channel `ch` (CSR: row starts, columns,
// values), in `storage`'s types. The arrays' lengths are checked against
// each other and against n, every row start and column index against its
// range, and every value for being finite, so that the runtime can index
// with them unchecked.
CsrMatrix read_kept(const fs::path& dir, int ch, std::size_t n, KeptStorage storage) {
  const fs::path rp = dir / bake_file::kept(ch, bake_file::KeptPart::kRowPtr),
                 cp = dir / bake_file::kept(ch, bake_file::KeptPart::kCol),
                 vp = dir / bake_file::kept(ch, bake_file::KeptPart::kValue);
  CsrMatrix k;
  k.n = n;
  k.row_ptr = read_vector(rp, read_npy_u32, n + 1);
  if (kept_columns_are_short(storage, n)) {
    const std::vector<std::uint16_t> col = read_vector(cp, read_npy_u16, std::nullopt);
    k.col.assign(col.begin(), col.end());
  } else {
    k.col = read_vector(cp, read_npy_u32, std::nullopt);
  }
  if (storage == KeptStorage::kFloat16) {
    const std::vector<std::uint16_t> bits = read_vector(vp, read_npy_half_bits, k.col.size());
    k.value.resize(bits.size());
    from_half_bits(bits, k.value);
  } else {
    k.value = read_vector(vp, read_npy_f32, k.col.size());
  }
  if (k.row_ptr.front() != 0)
    throw ReadError(rp.string(),
                    "row 0 starts at " + std::to_string(k.row_ptr.front()) + ", not 0");
  if (k.row_ptr.back() != k.col.size())
    throw ReadError(rp.string(), "the last row ends at " + std::to_string(k.row_ptr.back()) +
                                     ", but " + cp.filename().string() + " has " +
                                     std::to_string(k.col.size()) + " entries");
  for (std::size_t i = 0; i < n; ++i)
    if (k.row_ptr[i] > k.row_ptr[i + 1])
      throw ReadError(rp.string(), "row starts must not decrease (row " + std::to_string(i) + ")");
  for (std::size_t e = 0; e < k.col.size(); ++e)
    if (k.col[e] >= n)
      throw ReadError(cp.string(), "entry " + std::to_string(e) + " has column " +
                                       std::to_string(k.col[e]) + " of " + std::to_string(n));
  for (std::size_t e = 0; e < k.value.size(); ++e)
    if (!std::isfinite(k.value[e]))
      throw ReadError(vp.string(), "entry " + std::to_string(e) + " is not finite");
  return k;
}

CompressedMatrix read_compressed(const fs::path& dir, const json& c, std::size_t n) {
  const std::string manifest = (dir / bake_file::kManifest).string();
  CompressedMatrix m;
  m.n = n;
  m.padded = c.at("padded_size").get<std::size_t>();
  if (m.padded != (n + 3) / 4 * 4)
    throw ReadError(manifest, "compression.padded_size is " + std::to_string(m.padded) + " for " +
                                  std::to_string(n) + " patches (" +
                                  std::to_string((n + 3) / 4 * 4) + " expected)");
  m.channels = c.at("stored_channels").get<int>();
  if (m.channels != 1 && m.channels != 3)
    throw ReadError(manifest, "compression.stored_channels is " + std::to_string(m.channels) +
                                  " (1 or 3 expected)");
  m.codec = c.value("codec", "");
  m.encoder = c.value("encoder", "");
  m.ordering = c.value("ordering", "");
  m.kept_fraction = c.value("kept_fraction", 0.0);
  // Bakes from before half-precision kept entries have no kept_storage.
  const json storage = c.value("kept_storage", json("float32"));
  const std::optional<KeptStorage> kept_storage =
      storage.is_string() ? parse_kept_storage(storage.get<std::string>()) : std::nullopt;
  if (!kept_storage)
    throw ReadError(manifest, "compression.kept_storage is " + storage.dump() +
                                  " (\"float32\" or \"float16\" expected)");
  m.kept_storage = *kept_storage;
  const DdsImage dds = read_dds(dir / bake_file::kCompressedTransport);
  if (dds.width != m.padded || dds.height != m.padded)
    throw ReadError((dir / bake_file::kCompressedTransport).string(),
                    "is " + std::to_string(dds.width) + " x " + std::to_string(dds.height) +
                        ", the manifest says " + std::to_string(m.padded));
  m.format = dds.format;
  m.blocks = dds.blocks;
  const fs::path pf = dir / bake_file::kPermutation;
  NpyArray<std::uint32_t> perm = read_npy_u32(pf);
  require_shape(pf, perm.shape, {n});
  m.permutation = std::move(perm.data);
  if (!is_bijection(m.permutation))
    throw ReadError(pf.string(), "is not a permutation of 0.." + std::to_string(n - 1));
  for (const json& q : c.at("quantizers")) {
    LogQuantizer lq;
    lq.vmax = q.at("vmax").get<float>();
    lq.range = q.at("range").get<float>();
    if (!std::isfinite(lq.vmax) || !std::isfinite(lq.range) || !(lq.range > 0.0f))
      throw ReadError(manifest, "compression.quantizers[" + std::to_string(m.quantizers.size()) +
                                    "] has vmax " + std::to_string(lq.vmax) + " and range " +
                                    std::to_string(lq.range) + " (finite, range > 0 expected)");
    m.quantizers.push_back(lq);
  }
  for (int ch = 0; ch < m.channels; ++ch) m.kept.push_back(read_kept(dir, ch, n, m.kept_storage));
  if (m.quantizers.size() != static_cast<std::size_t>(m.channels))
    throw ReadError(manifest, "compression.quantizers has " + std::to_string(m.quantizers.size()) +
                                  " entries for " + std::to_string(m.channels) +
                                  " stored channels");
  return m;
}

}  // namespace

json read_manifest_json(const fs::path& path) {
  const std::size_t bytes = regular_file_size<ReadError>(path);
  if (bytes > kMaxManifestBytes)
    throw ReadError(path.string(), "is " + std::to_string(bytes) +
                                       " bytes; a bake manifest is at most " +
                                       std::to_string(kMaxManifestBytes));
  std::ifstream in(path);
  if (!in) throw ReadError(path.string(), "cannot open file");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw ReadError(path.string(), std::string("is not valid JSON: ") + e.what());
  }
}

bool is_bake_folder(const fs::path& path) {
  std::error_code ec;
  return fs::is_directory(path, ec) && fs::is_regular_file(path / bake_file::kManifest, ec);
}

std::optional<std::vector<float>> read_form_factors(const fs::path& dir, std::size_t n) {
  const fs::path file = dir / bake_file::kFormFactors;
  std::error_code ec;
  if (!fs::exists(file, ec)) return std::nullopt;
  NpyArray<float> f = read_npy_f32(file);
  require_shape(file, f.shape, {n, n});
  return std::move(f.data);
}

LoadedBake BakeReader::read(const fs::path& dir, Dense dense) {
  // A manifest with missing or mistyped entries is a damaged bake: say so,
  // naming the file, rather than letting a JSON exception escape.
  try {
    return read_checked(dir, dense);
  } catch (const nlohmann::json::exception& e) {
    throw ReadError((dir / bake_file::kManifest).string(),
                    std::string("lacks an entry or has one of the wrong type: ") + e.what());
  }
}

LoadedBake BakeReader::read_checked(const fs::path& dir, Dense dense) {
  LoadedBake b;
  b.dir = dir;
  b.manifest = read_manifest(dir);
  const fs::path manifest_path = dir / bake_file::kManifest;
  // Every array below is checked against this count, and through it
  // against the files' sizes, so a manifest cannot ask for more memory than
  // the bake's files hold; with 0 patches, shapes such as (lights, 0, 3)
  // would hold no data and bound nothing.
  const auto n = b.manifest.at("counts").at("patches").get<std::size_t>();
  if (n == 0) throw ReadError(manifest_path.string(), "counts.patches is 0");
  try {
    b.description = describe_bake(b.manifest, manifest_path);
  } catch (const Error& e) {
    throw ReadError(manifest_path.string(), std::string(e.what()).substr(e.where().size() + 2));
  }
  read_patches(dir, n, b);
  read_seen_weights(dir, b);
  read_carried_polygons(dir, b.samples);
  read_voxel_cells(dir, b);
  const json& t = b.manifest.at("transport");
  b.channel_of_rgb = t.at("channel_of_rgb").get<std::array<int, 3>>();
  b.stored_channels = static_cast<int>(t.at("channels").size());
  if (b.stored_channels < 1 || b.stored_channels > 3)
    throw ReadError(manifest_path.string(), "transport.channels has " +
                                                std::to_string(b.stored_channels) +
                                                " entries (1 to 3 expected)");
  for (int c : b.channel_of_rgb)
    if (c < 0 || c >= b.stored_channels)
      throw ReadError(manifest_path.string(), "transport.channel_of_rgb names channel " +
                                                  std::to_string(c) + " of " +
                                                  std::to_string(b.stored_channels));
  const json& c = b.manifest.at("compression");
  if (c.contains("stored_channels")) b.compressed = read_compressed(dir, c, n);
  const fs::path tf = dir / bake_file::kDenseTransport;
  const bool want_dense =
      dense == Dense::kRead || (dense == Dense::kIfNotCompressed && !b.compressed);
  if (want_dense && fs::exists(tf)) {
    const NpyArray<float> matrix = read_npy_f32(tf);
    const auto channels = static_cast<std::size_t>(b.stored_channels);
    require_shape(tf, matrix.shape, {channels, n, n});
    for (std::size_t ch = 0; ch < channels; ++ch)
      b.dense.emplace_back(matrix.data.begin() + static_cast<std::ptrdiff_t>(ch * n * n),
                           matrix.data.begin() + static_cast<std::ptrdiff_t>((ch + 1) * n * n));
  }
  if (!b.compressed && b.dense.empty())
    throw ReadError(dir.string(), dense != Dense::kSkip
                                      ? "holds no transport matrix (T.dds or T.npy)"
                                      : "holds no compressed transport matrix (T.dds)");
  const fs::path lf = dir / bake_file::kLightsFirstHit;
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
