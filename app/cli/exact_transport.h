#pragma once
// The exact multi-bounce matrix and the indirect-light probe that
// `bounce bench compress` compresses and measures against, from either
//   * a scene: baked here with the dense codec (exact T kept, no pictures), or
//   * a bake folder written by `bounce bake` that holds T.npy (the bake was
//     dense or made with --dump-matrices), read with the one bake reader.
#include <filesystem>
#include <string>
#include <vector>

#include "bounce/bake.h"
#include "bounce/bake_folder.h"
#include "bounce/compression.h"

namespace bounce::cli {

struct ExactTransport {
  std::string name;    // scene name, or the bake folder's
  std::string source;  // "baked now (...)" or "bake folder <path>"
  std::size_t n = 0;
  std::vector<std::vector<float>> channels;  // stored channels, n x n row-major each
  IndirectLightProbe probe;
  double bake_seconds = 0.0;  // scene: time of the bake; 0 for a folder

  std::vector<const float*> matrices() const;
};

// Reads a bake folder with the one bake reader (folder/bake_reader.h); throws
// bounce::Error naming the missing or malformed file (T.npy missing: says to
// bake with --dump-matrices).
ExactTransport read_bake_folder(const std::filesystem::path& folder);

// Loads and bakes a scene with `settings` (the codec forced to dense, no
// pictures, no matrix dumps): a full bake up to the transport matrix.
ExactTransport bake_exact_transport(const std::string& scene_path, BakeSettings settings,
                                    Progress& progress);

}  // namespace bounce::cli
