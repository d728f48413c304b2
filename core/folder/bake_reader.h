#pragma once
// Reads a bake folder (docs/bake-format.md) back: what `bounce solve`, the
// runtime benchmarks and the studio need to light a baked scene without
// baking again. Every problem (missing file, wrong shape, a manifest from
// another format version) throws bounce::Error naming the file.
#include <array>
#include <filesystem>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "compress/codec.h"
#include "compress/compression_error.h"
#include "folder/bake_description.h"
#include "folder/bake_format.h"
#include "patches/patch_set.h"
#include "patches/samples.h"

namespace bounce {

struct LoadedBake {
  std::filesystem::path dir;
  nlohmann::json manifest;
  // The manifest's scene, grid, key and bounces, typed: what front ends read.
  BakeDescription description;
  // Patches with their member samples (position, normal, area, albedo,
  // voxel, triangle): enough to compute direct light on the patches.
  PatchSet patches;
  SampleSet samples;
  // Each sample's patch, or -1 when its patch was left out.
  std::vector<std::int32_t> patch_of_sample;
  // Each occupied voxel's cell (i, j, k) in the bake's grid (voxels.npy):
  // with the carried polygons' triangles, what SurfacePatchLookup needs to
  // find the patch at a surface point.
  std::vector<glm::ivec3> voxel_cells;
  std::array<int, 3> channel_of_rgb{0, 1, 2};
  int stored_channels = 0;
  // The compressed matrix, when the bake stored one.
  std::optional<CompressedMatrix> compressed;
  // The exact matrices (stored channels, n x n each), when T.npy is there
  // (dense bakes, or --dump-matrices).
  std::vector<std::vector<float>> dense;
  // The evaluation lights' first-hit vectors and the patch areas.
  IndirectLightProbe probe;

  std::size_t size() const { return patches.size(); }
};

class BakeReader {
 public:
  class ReadError : public Error {
   public:
    using Error::Error;
  };

  // Whether to read the exact matrix T.npy (it can be large).
  enum class Dense {
    kSkip,             // never
    kIfNotCompressed,  // only when the bake has no compressed matrix (a dense bake)
    kRead,             // whenever it is there
  };

  // `with_dense`: also read T.npy when present.
  static LoadedBake read(const std::filesystem::path& dir, bool with_dense = true) {
    return read(dir, with_dense ? Dense::kRead : Dense::kSkip);
  }
  static LoadedBake read(const std::filesystem::path& dir, Dense dense);

 private:
  static LoadedBake read_checked(const std::filesystem::path& dir, Dense dense);
};

// Real manifests are a few KiB to a few hundred KiB; a larger one is not a
// manifest, and parsing it would take memory in proportion.
inline constexpr std::size_t kMaxManifestBytes = std::size_t(16) << 20;

// A bake manifest (or any JSON file of a bake folder) parsed; throws
// BakeReader::ReadError naming the file when it is missing, not a regular
// file, larger than kMaxManifestBytes or not JSON. Checks nothing else.
nlohmann::json read_manifest_json(const std::filesystem::path& path);

// The form factors F.npy (n x n, row = source) of the bake in `dir`, when it
// holds them (a bake made with --dump-matrices); nullopt when the file is
// absent. Throws BakeReader::ReadError naming the file when it is not n x n
// float32. `n` is the bake's patch count (LoadedBake::size()).
std::optional<std::vector<float>> read_form_factors(const std::filesystem::path& dir,
                                                    std::size_t n);

}  // namespace bounce
