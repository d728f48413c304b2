#pragma once
// The bake folder's layout (docs/bake-format.md) in one place: the format's
// name and version, every file name and every column of the NumPy tables.
// The writer, the reader and everything else that opens a bake folder use
// these names, so a change to the format is made here and nowhere else.
#include <cstddef>
#include <filesystem>
#include <string>

namespace bounce {

// The manifest's "format" and "format_version". 2: the multi-bounce matrix
// (dense T.npy or compressed T.dds + CSR) and its pictures joined the folder.
inline constexpr const char* kBakeFormatName = "bounce-bake";
inline constexpr int kBakeFormatVersion = 2;

// File names inside a bake folder.
namespace bake_file {
inline constexpr const char* kManifest = "manifest.json";
inline constexpr const char* kPatches = "patches.npy";
inline constexpr const char* kVoxels = "voxels.npy";
inline constexpr const char* kSamples = "samples.npy";
inline constexpr const char* kCarriedPolygons = "carried_polygons.npy";
inline constexpr const char* kCarriedArea = "carried_area.npy";
inline constexpr const char* kCarriedVertices = "carried_vertices.npy";
inline constexpr const char* kClosure = "closure.npy";
inline constexpr const char* kGatherFirst = "gather_first.npy";
inline constexpr const char* kGatherSource = "gather_source.npy";
inline constexpr const char* kGatherWeight = "gather_weight.npy";
inline constexpr const char* kGatherCluster = "gather_cluster.npy";
inline constexpr const char* kGatherShare = "gather_share.npy";
inline constexpr const char* kGatherSeenFirst = "gather_seen_first.npy";
inline constexpr const char* kGatherSeenSample = "gather_seen_sample.npy";
inline constexpr const char* kGatherSeenWeight = "gather_seen_weight.npy";
inline constexpr const char* kGatherSpotFirst = "gather_spot_first.npy";
inline constexpr const char* kGatherSpotWeight = "gather_spot_weight.npy";
inline constexpr const char* kGatherNearPosition = "gather_near_position.npy";
inline constexpr const char* kGatherNearNormal = "gather_near_normal.npy";
inline constexpr const char* kGatherNearAlbedo = "gather_near_albedo.npy";
inline constexpr const char* kGatherNearPatch = "gather_near_patch.npy";
// The light probes: their positions, and their directions' gather in the
// files of the vertices' gather with this prefix instead of "gather_".
inline constexpr const char* kProbePositions = "probe_position.npy";
inline constexpr const char* kProbeGatherPrefix = "probe_gather_";
// The probe volumes' lattices, when the bake has volumes.
inline constexpr const char* kProbeVolumes = "probe_volume.npy";
inline constexpr const char* kGatherPrefix = "gather_";  // of the names above
inline constexpr const char* kFormFactors = "F.npy";
inline constexpr const char* kDenseTransport = "T.npy";
inline constexpr const char* kLightsFirstHit = "lights_first_hit.npy";
inline constexpr const char* kCompressedTransport = "T.dds";
inline constexpr const char* kPermutation = "permutation.npy";
inline constexpr const char* kPictureTransport = "T.png";
inline constexpr const char* kPictureReordered = "T_reordered.png";
inline constexpr const char* kPictureError = "T_error.png";
inline constexpr const char* kPictureErrorBlocks = "T_error_blocks.png";

// The three CSR arrays of the entries of stored channel `channel` that a
// compressed bake keeps exactly: T_kept_<channel>_{row_ptr,col,value}.npy.
enum class KeptPart { kRowPtr, kCol, kValue };
inline std::string kept(int channel, KeptPart part) {
  const char* suffix = part == KeptPart::kRowPtr ? "_row_ptr.npy"
                       : part == KeptPart::kCol  ? "_col.npy"
                                                 : "_value.npy";
  return "T_kept_" + std::to_string(channel) + suffix;
}
}  // namespace bake_file

// Columns of patches.npy (float32, one row per patch): the first column of
// each field and the row width.
namespace patch_column {
inline constexpr std::size_t kPosition = 0;  // x, y, z
inline constexpr std::size_t kNormal = 3;    // x, y, z
inline constexpr std::size_t kArea = 6;
inline constexpr std::size_t kAlbedo = 7;  // r, g, b
inline constexpr std::size_t kVoxel = 10;
inline constexpr std::size_t kMesh = 11;
inline constexpr std::size_t kEmission = 12;  // r, g, b
inline constexpr std::size_t kCount = 15;
}  // namespace patch_column

// Columns of voxels.npy (float32, one row per occupied voxel).
namespace voxel_column {
inline constexpr std::size_t kCell = 0;    // i, j, k
inline constexpr std::size_t kCentre = 3;  // x, y, z
inline constexpr std::size_t kArea = 6;
inline constexpr std::size_t kSamples = 7;
inline constexpr std::size_t kPatches = 8;
inline constexpr std::size_t kCount = 9;
}  // namespace voxel_column

// Columns of samples.npy (float32, one row per sample).
namespace sample_column {
inline constexpr std::size_t kPosition = 0;  // x, y, z
inline constexpr std::size_t kNormal = 3;    // x, y, z
inline constexpr std::size_t kArea = 6;
inline constexpr std::size_t kAlbedo = 7;  // r, g, b
inline constexpr std::size_t kVoxel = 10;
inline constexpr std::size_t kPatch = 11;  // -1: its patch was left out
inline constexpr std::size_t kTriangle = 12;
inline constexpr std::size_t kCount = 13;
}  // namespace sample_column

// Columns of carried_polygons.npy (uint32, one row per polygon).
namespace carried_polygon_column {
inline constexpr std::size_t kSample = 0;
inline constexpr std::size_t kFirstVertex = 1;
inline constexpr std::size_t kVertexCount = 2;
// Without the next two (bakes made before they were written), a reader
// knows the polygons' shapes but not which triangle each lies on.
inline constexpr std::size_t kCountWithoutTriangles = 3;
inline constexpr std::size_t kTriangle = 3;  // the scene triangle it lies on
inline constexpr std::size_t kBack = 4;      // 1: its back side (two-sided triangles)
inline constexpr std::size_t kCount = 5;
}  // namespace carried_polygon_column

// Columns of closure.npy (float32, one row per patch).
namespace closure_column {
inline constexpr std::size_t kClosure = 0;
inline constexpr std::size_t kRowScale = 1;
inline constexpr std::size_t kCount = 2;
}  // namespace closure_column

// Three components per vertex (carried_vertices.npy) and per patch and light
// (lights_first_hit.npy).
inline constexpr std::size_t kBakeVectorComponents = 3;

// True when `path` is a folder holding a manifest.json: what every front end
// asks before treating a path as a bake rather than a scene. Never throws.
bool is_bake_folder(const std::filesystem::path& path);

}  // namespace bounce
