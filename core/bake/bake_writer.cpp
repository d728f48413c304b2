#include "bake/bake_writer.h"

#include <string>
#include <vector>

#include "bake/bake_manifest.h"
#include "bake/bake_pictures.h"
#include "compress/dds.h"
#include "folder/final_gather_files.h"
#include "folder/light_probe_files.h"
#include "io/atomic_file.h"
#include "io/npy.h"

namespace bounce {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr std::size_t kPatchColumns = patch_column::kCount;
constexpr std::size_t kVoxelColumns = voxel_column::kCount;
constexpr std::size_t kSampleColumns = sample_column::kCount;

std::vector<float> patch_rows(const BakeResult& r) {
  std::vector<float> rows;
  rows.reserve(r.patches.size() * kPatchColumns);
  for (const Patch& p : r.patches.patches) {
    rows.insert(rows.end(),
                {p.position.x, p.position.y, p.position.z, p.normal.x, p.normal.y, p.normal.z,
                 p.area, p.albedo.r, p.albedo.g, p.albedo.b, static_cast<float>(p.voxel),
                 static_cast<float>(p.mesh), p.emission.r, p.emission.g, p.emission.b});
  }
  return rows;
}

std::vector<float> voxel_rows(const BakeResult& r) {
  std::vector<std::uint32_t> patch_count(r.voxels.voxels.size(), 0);
  for (const Patch& p : r.patches.patches) patch_count[p.voxel]++;
  std::vector<float> rows;
  rows.reserve(r.voxels.voxels.size() * kVoxelColumns);
  for (std::size_t v = 0; v < r.voxels.voxels.size(); ++v) {
    const OccupiedVoxel& ov = r.voxels.voxels[v];
    const glm::vec3 c = r.voxels.grid.cell_bounds(ov.coord).center();
    rows.insert(rows.end(), {static_cast<float>(ov.coord.x), static_cast<float>(ov.coord.y),
                             static_cast<float>(ov.coord.z), c.x, c.y, c.z, ov.area,
                             static_cast<float>(r.samples.first[v + 1] - r.samples.first[v]),
                             static_cast<float>(patch_count[v])});
  }
  return rows;
}

std::vector<float> sample_rows(const BakeResult& r) {
  std::vector<float> rows;
  rows.reserve(r.samples.samples.size() * kSampleColumns);
  for (std::size_t k = 0; k < r.samples.samples.size(); ++k) {
    const Sample& s = r.samples.samples[k];
    rows.insert(rows.end(),
                {s.position.x, s.position.y, s.position.z, s.normal.x, s.normal.y, s.normal.z,
                 s.area, s.albedo.r, s.albedo.g, s.albedo.b, static_cast<float>(s.voxel),
                 static_cast<float>(r.patch_of_sample[k]), static_cast<float>(s.triangle)});
  }
  return rows;
}

// The polygons of surface each sample carries (SampleSet::carried), so that
// a bake read back integrates point lights over them as the bake did
// (runtime/direct_light.cpp) instead of evaluating them at the samples.
void write_carried_polygons(const fs::path& dir, const SampleSet& samples) {
  std::vector<std::uint32_t> polygons;
  std::vector<float> areas, vertices;
  polygons.reserve(carried_polygon_column::kCount * samples.carried.size());
  areas.reserve(samples.carried.size());
  vertices.reserve(3 * samples.carried_vertices.size());
  for (const glm::vec3& v : samples.carried_vertices)
    vertices.insert(vertices.end(), {v.x, v.y, v.z});
  if (samples.carried_first.size() == samples.samples.size() + 1)
    for (std::size_t k = 0; k < samples.samples.size(); ++k)
      for (std::uint32_t c = samples.carried_first[k]; c < samples.carried_first[k + 1]; ++c) {
        const CarriedArea& piece = samples.carried[c];
        polygons.insert(polygons.end(), {static_cast<std::uint32_t>(k), piece.first_vertex,
                                         piece.vertex_count, piece.triangle, piece.back ? 1u : 0u});
        areas.push_back(piece.area);
      }
  write_npy(dir / bake_file::kCarriedPolygons, std::span<const std::uint32_t>(polygons),
            {areas.size(), carried_polygon_column::kCount});
  write_npy(dir / bake_file::kCarriedArea, std::span<const float>(areas), {areas.size()});
  write_npy(dir / bake_file::kCarriedVertices, std::span<const float>(vertices),
            {samples.carried_vertices.size(), kBakeVectorComponents});
}

// T.npy: every stored channel, float32 [channels x n x n].
void write_dense_transport(const fs::path& path, const TransportResult& t) {
  std::vector<std::span<const float>> channels;
  for (const ChannelTransport& c : t.channels) channels.emplace_back(c.t);
  write_npy(path, channels, {t.channels.size(), t.n, t.n});
}

}  // namespace

namespace {

// The folder's contents, written into `dir` (the temporary folder).
json write_bake_files(const AtomicDirectory& dir, const Scene& scene, const BakeResult& r,
                      const Diagnostics& diagnostics);

// An error from writing one file names the file by its temporary path
// (".NAME.partial-PID-N/patches.npy"), which is gone once the failed bake
// has cleaned up. Say it about the bake folder the user asked for instead.
[[noreturn]] void rethrow_for_target(const AtomicDirectory& dir, const fs::path& file,
                                     const std::string& why) {
  if (file.empty()) throw IoError(dir.target().string(), "cannot write the bake: " + why);
  fs::path relative = file.lexically_relative(dir.path());
  if (relative.empty() || *relative.begin() == "..") relative = file;
  throw IoError(dir.target().string(), "cannot write " + relative.string() + ": " + why);
}

}  // namespace

json write_bake(const fs::path& out_dir, const Scene& scene, const BakeResult& r,
                const Diagnostics& diagnostics) {
  AtomicDirectory dir(out_dir);
  json m;
  try {
    m = write_bake_files(dir, scene, r, diagnostics);
  } catch (const Cancelled&) {
    throw;
  } catch (const Error& e) {
    // Error::what() is "<where>: <why>"; keep <why>, name <where> relative to the folder.
    std::string why = e.what();
    if (!e.where().empty() && why.rfind(e.where() + ": ", 0) == 0)
      why = why.substr(e.where().size() + 2);
    rethrow_for_target(dir, e.where(), why);
  } catch (const fs::filesystem_error& e) {
    rethrow_for_target(dir, e.path1(), e.code().message());
  }
  dir.commit();
  return m;
}

namespace {

json write_bake_files(const AtomicDirectory& dir, const Scene& scene, const BakeResult& r,
                      const Diagnostics& diagnostics) {
  json files = json::array();
  auto record = [&](const std::string& name, const std::string& what) {
    files.push_back(
        {{"name", name}, {"bytes", fs::file_size(dir.path() / name)}, {"content", what}});
  };
  const std::size_t n = r.patches.size();
  write_npy(dir.path() / bake_file::kPatches, patch_rows(r), {n, kPatchColumns});
  record(bake_file::kPatches, "float32 [patches x " + std::to_string(kPatchColumns) +
                                  "]: position xyz, normal xyz, area, albedo rgb, "
                                  "voxel index, mesh index, emission rgb");
  write_npy(dir.path() / bake_file::kVoxels, voxel_rows(r),
            {r.voxels.voxels.size(), kVoxelColumns});
  record(bake_file::kVoxels, "float32 [occupied voxels x " + std::to_string(kVoxelColumns) +
                                 "]: cell ijk, centre xyz, surface area, "
                                 "sample count, patch count");
  write_npy(dir.path() / bake_file::kSamples, sample_rows(r),
            {r.samples.samples.size(), kSampleColumns});
  record(bake_file::kSamples, "float32 [samples x " + std::to_string(kSampleColumns) +
                                  "]: position xyz, normal xyz, area, albedo rgb, "
                                  "voxel index, patch index (-1 = left out), triangle index");
  write_carried_polygons(dir.path(), r.samples);
  record(bake_file::kCarriedPolygons,
         "uint32 [polygons x 5]: sample index, first vertex, vertex count, scene triangle and "
         "side (1: back) of each planar polygon of surface a sample stands for, in sample order");
  record(bake_file::kCarriedArea, "float32 [polygons]: the area each polygon stands for");
  record(bake_file::kCarriedVertices, "float32 [vertices x 3]: the polygons' vertices xyz");
  if (r.closure.closure.size() == n && r.balance.row_scale.size() == n) {
    std::vector<float> rows;
    rows.reserve(2 * n);
    for (std::size_t p = 0; p < n; ++p)
      rows.insert(rows.end(), {r.closure.closure[p], r.balance.row_scale[p]});
    write_npy(dir.path() / bake_file::kClosure, rows, {n, closure_column::kCount});
    record(bake_file::kClosure,
           "float32 [patches x 2]: closure (share of the patch's light that lands on sampled "
           "surface, the row sum F is balanced to), row scale the balancing applied (balanced / "
           "raw row sum)");
  }
  if (r.vertex_gather.points() > 0) {
    write_final_gather(dir.path(), r.vertex_gather);
    record(bake_file::kGatherFirst, "uint32 [lit-mesh vertices + 1]: final gather row starts");
    record(bake_file::kGatherSource,
           "uint32 [entries]: patch each entry gathers from, or patches + cluster index, or "
           "patches + clusters + sample index, or patches + clusters + samples + near source");
    record(bake_file::kGatherWeight, "float32 [entries]: vertex-to-patch (or cluster) form factor");
    record(bake_file::kGatherCluster, "uint32 [patches]: cluster of each patch");
    record(bake_file::kGatherShare,
           "float32 [patches]: each patch's share of its cluster's light (of the rays folded "
           "into the cluster)");
    if (!r.vertex_gather.seen_first.empty()) {
      record(bake_file::kGatherSeenFirst,
             "uint32 [patches + 1]: row starts of each patch's seen weights");
      record(bake_file::kGatherSeenSample, "uint32 [entries]: a sample of the patch");
      record(bake_file::kGatherSeenWeight,
             "float32 [entries]: its share of the gather's rays read through the patch: a "
             "patch entry's light is the sum of share x the sample's light");
    }
    if (r.vertex_gather.near.size() > 0) {
      record(bake_file::kGatherNearPosition,
             "float32 [near sources x 3]: where each near source is lit every frame");
      record(bake_file::kGatherNearNormal, "float32 [near sources x 3]: the side it is lit on");
      record(bake_file::kGatherNearAlbedo, "float32 [near sources x 3]: its mean albedo");
      record(bake_file::kGatherNearPatch,
             "uint32 [near sources]: the patch whose multi-bounce light T b it carries");
    }
    if (!r.vertex_gather.spot_first.empty()) {
      record(bake_file::kGatherSpotFirst,
             "uint32 [samples + 1]: row starts of each sample's spots, the last near sources");
      record(bake_file::kGatherSpotWeight,
             "float32 [spots]: the spot's share of the sample's light (of the far rays that "
             "landed on the sample's spots)");
    }
  }
  if (placed_probes(r) != ProbePlacementMode::Off) {
    write_light_probes(dir.path(), r.light_probes);
    record(bake_file::kProbePositions, "float32 [probes x 3]: light probe positions");
    if (!r.light_probes.volumes.empty())
      record(bake_file::kProbeVolumes,
             "float32 [volumes x 9]: each probe volume's lattice (origin x y z, spacing, cells "
             "x y z) and its probes (first, count)");
    const auto probe_file = [](const char* name) {
      return gather_file_name(bake_file::kProbeGatherPrefix, name);
    };
    record(probe_file(bake_file::kGatherFirst),
           "uint32 [probes x 14 + 1]: row starts of the probes' gather, probe p's direction k "
           "in row 14 p + k");
    record(probe_file(bake_file::kGatherSource), "uint32 [entries]: as gather_source.npy");
    record(probe_file(bake_file::kGatherWeight),
           "float32 [entries]: direction-to-source form factor");
    record(probe_file(bake_file::kGatherCluster), "uint32 [patches]: cluster of each patch");
    record(probe_file(bake_file::kGatherShare),
           "float32 [patches]: each patch's share of its cluster's light");
    if (!r.light_probes.gather.seen_first.empty()) {
      record(probe_file(bake_file::kGatherSeenFirst),
             "uint32 [patches + 1]: row starts of each patch's seen weights");
      record(probe_file(bake_file::kGatherSeenSample), "uint32 [entries]: a sample of the patch");
      record(probe_file(bake_file::kGatherSeenWeight),
             "float32 [entries]: its share of the probes' rays read through the patch");
    }
  }
  if (r.settings.dump_matrices) {
    write_npy(dir.path() / bake_file::kFormFactors, r.form_factors.values, {n, n});
    record(bake_file::kFormFactors, "float32 [patches x patches]: form factors, row = source");
  }
  if (!r.storage.compressed || r.settings.dump_matrices) {
    write_dense_transport(dir.path() / bake_file::kDenseTransport, r.transport);
    record(bake_file::kDenseTransport,
           "float32 [stored channels x patches x patches]: multi-bounce matrix, exact; "
           "channel_of_rgb in the manifest maps R, G, B to its channels");
  }
  {
    std::vector<float> b;
    for (const auto& light : r.probe.first_hit)
      for (const glm::vec3& v : light) b.insert(b.end(), {v.r, v.g, v.b});
    write_npy(dir.path() / bake_file::kLightsFirstHit, b,
              {r.probe.first_hit.size(), n, kBakeVectorComponents});
    record(bake_file::kLightsFirstHit,
           "float32 [evaluation lights x patches x 3]: light leaving each patch after the first "
           "hit (albedo x direct irradiance) for the scene's lights and four unit test lights; "
           "the indirect-light error is measured with these");
  }
  if (r.storage.compressed) {
    const CompressedMatrix& c = *r.storage.compressed;
    const auto side = static_cast<std::uint32_t>(c.padded);
    write_dds(dir.path() / bake_file::kCompressedTransport, c.format, side, side, c.blocks);
    record(bake_file::kCompressedTransport,
           std::string(c.format == DdsFormat::kBc4 ? "BC4" : "BC1") +
               " [padded x padded]: log codes of the reordered matrix (row/column k = "
               "patch permutation[k]); see compression.quantizers");
    write_npy(dir.path() / bake_file::kPermutation, c.permutation, {n});
    record(bake_file::kPermutation,
           "uint32 [patches]: stored row/column k holds patch permutation[k]");
    for (std::size_t ch = 0; ch < c.kept.size(); ++ch) {
      const CsrMatrix& k = c.kept[ch];
      const int channel = static_cast<int>(ch);
      const std::string row_ptr = bake_file::kept(channel, bake_file::KeptPart::kRowPtr),
                        col = bake_file::kept(channel, bake_file::KeptPart::kCol),
                        value = bake_file::kept(channel, bake_file::KeptPart::kValue);
      write_npy(dir.path() / row_ptr, k.row_ptr, {k.row_ptr.size()});
      record(row_ptr,
             "uint32 [patches + 1]: CSR row starts of the kept entries of stored channel " +
                 std::to_string(ch));
      if (kept_columns_are_short(c.kept_storage, n)) {
        const std::vector<std::uint16_t> short_col(k.col.begin(), k.col.end());
        write_npy(dir.path() / col, short_col, {short_col.size()});
        record(col, "uint16 [kept]: CSR column (patch order)");
      } else {
        write_npy(dir.path() / col, k.col, {k.col.size()});
        record(col, "uint32 [kept]: CSR column (patch order)");
      }
      if (c.kept_storage == KeptStorage::kFloat16) {
        std::vector<std::uint16_t> bits(k.value.size());
        to_half_bits(k.value, bits);
        write_npy_half(dir.path() / value, bits, {bits.size()});
        record(value, "float16 [kept]: CSR values, rounded to half precision");
      } else {
        write_npy(dir.path() / value, k.value, {k.value.size()});
        record(value, "float32 [kept]: CSR values, exact");
      }
    }
  }
  if (r.settings.pictures)
    for (const WrittenPicture& p : write_matrix_pictures(dir.path(), r)) record(p.name, p.content);
  json m = make_manifest(scene, r, diagnostics);
  m["files"] = files;
  {
    AtomicFile manifest(dir.path() / bake_file::kManifest);
    manifest.stream() << m.dump(2) << '\n';
    manifest.commit();
  }
  return m;
}

}  // namespace

}  // namespace bounce
