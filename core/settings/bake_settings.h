#pragma once
// Every knob of a bake, with the defaults a user gets when they say nothing.
#include <cstdint>
#include <optional>
#include <string>

#include "base/error.h"
#include "compress/codec.h"
#include "runtime/final_gather_settings.h"
#include "scene/scene.h"
#include "transport/transport_settings.h"

namespace bounce {

enum class PatchMode { Virtual, Voxel };

// How the multi-bounce matrix is stored.
//   Auto:           light-weighted, unless the matrix is so small that
//                   compression does not pay (dense float RGB under
//                   kDenseUpToBytes): then dense, and said so.
//   Dense:          float32, no compression (exact).
//   LargestEntries: the published pipeline, the baseline ("paper").
//   LightWeighted:  our codec, always, whatever the size ("ours").
enum class CodecChoice { Auto, Dense, LargestEntries, LightWeighted };

// Whether the finished dense N x N matrices (F, T) live in memory-mapped
// temporary files (bake/out_of_core.h): Auto when the transport's dense
// footprint would exceed half the machine's memory; On always, Off never.
// The result is the same bit for bit either way.
enum class OutOfCore { Auto, On, Off };

// Which light probes the bake places (runtime/light_probe_placement.h):
//   On:          next to the surfaces, and in every probe volume;
//   VolumesOnly: only in the probe volumes;
//   Off:         none;
//   Auto:        the scene's bake block decides, else On, except that a
//                grid with more candidates than light_probes_max places
//                none next to the surfaces and says so (On refuses it).
enum class ProbePlacementMode { Auto, On, VolumesOnly, Off };

struct BakeSettings {
  // Names the setting (settings_table.h), not a front end's control for it:
  // "setting 'error_budget': ...". The command line adds its option's name.
  class InvalidSetting : public Error {
   public:
    InvalidSetting(std::string setting, const std::string& what)
        : Error("setting '" + setting + "'", what), setting_(std::move(setting)) {}
    const std::string& setting() const noexcept { return setting_; }

   private:
    std::string setting_;
  };

  // Exactly one of these two decides the grid; with neither, the scene's
  // defaults apply, then `kDefaultVoxelResolution`.
  std::optional<int> voxel_resolution;
  std::optional<int> patches_total;
  // Unset: the scene's bake block, else the default below.
  std::optional<int> patches_per_voxel;
  PatchMode patch_mode = PatchMode::Virtual;
  std::optional<int> samples_per_face;
  int visibility_rays = 8;  // rays per patch pair
  // Rays per patch measuring its closure (formfactor/closure.h), to which the
  // form-factor rows are then balanced (formfactor/balance.h); 0: neither,
  // the raw quadrature is kept.
  int closure_rays = 512;
  // The final gather's defaults are its own (runtime/final_gather_settings.h).
  // Rays per vertex of the lit mesh for the final gather
  // (runtime/final_gather.h) the bake stores; 0: none, the run time spreads
  // patch light to vertices from the nearest patches instead.
  int final_gather_rays = FinalGatherSettings{}.rays;
  // Within this many voxels of a vertex its gather rays read near sources,
  // lit at their own position each frame (runtime/final_gather.h); 0: none.
  double final_gather_near = FinalGatherSettings{}.near;
  // Near sources fewer of the gather's rays landed in go back to the sample
  // or patch the vertices read for that surface (runtime/final_gather.h):
  // each near source costs a shadow ray per light every frame.
  int final_gather_near_min_rays = FinalGatherSettings{}.near_min_rays;
  // Points per sample where the vertices' far rays landed on it, each lit
  // every frame, whose light is the sample's (runtime/final_gather.h, spots);
  // 0: samples are lit at their centres.
  int final_gather_spots = FinalGatherSettings{}.spots;
  // Light probes in the empty cells next to surfaces and in the probe
  // volumes, gathered like the vertices (runtime/light_probes.h,
  // runtime/light_probe_placement.h), and the most they may number: more
  // is refused before any is traced. A probe holds about 2000 gather
  // entries (1800-2300 on Sponza and the Cornell box), some 25 KB while the
  // bake runs: 100000 are 2.5 GB.
  ProbePlacementMode light_probes = ProbePlacementMode::Auto;
  int light_probes_max = 100000;
  // Probe volumes as text (runtime/probe_volume.h); empty: the scene's bake
  // block's, else none.
  std::string light_probe_volumes;
  std::uint64_t seed = 1;
  bool dump_matrices = false;

  TransportSettings transport;
  CodecChoice codec = CodecChoice::Auto;
  // Share of each channel's entries kept exactly. Unset: kPaperKeptFraction
  // for `paper`; for ours the smallest fraction of kKeptFractionLadder that meets
  // the error budget.
  std::optional<double> kept_fraction;
  // Relative RMS error of the indirect light the compressed matrix may cause
  // (ours): area-weighted over patches and colour channels, on the worst of
  // the evaluation lights (compress/compression_error.h) that put any
  // indirect light on the patches. Unset: the scene's bake block, else
  // kDefaultErrorBudget.
  std::optional<double> error_budget;
  // Largest size the error budget's search may give the compressed matrix, as
  // a share of dense float32 RGB (3 N^2 x 4 bytes). Unset: kDefaultSizeLimit.
  std::optional<double> size_limit;
  // Row/column ordering before block encoding (paper, ours). Unset: the
  // codec's own (paper: the greedy tour, 2 passes; ours: sketch + tour).
  std::optional<OrderingMethod> ordering;
  // Matrix pictures (PNG) in the bake folder.
  bool pictures = true;
  OutOfCore out_of_core = OutOfCore::Auto;
  // The temporary matrix files' folder; empty: $TMPDIR, else /tmp.
  std::string out_of_core_dir;

  static constexpr int kDefaultVoxelResolution = 16;
  // 3: a voxel at a box corner holds three orientations, and clustering merges
  // by normal first, so three patches keep every corner's faces apart; on a
  // flat wall the three subdivide the surface instead.
  static constexpr int kDefaultPatchesPerVoxel = 3;
  static constexpr int kDefaultSamplesPerFace = 4;  // 4x4 rays per voxel face: 96 per voxel
  // Dense float RGB of 1 MiB is N = 295 patches: a dense product costs under a
  // millisecond and compression would only add error.
  static constexpr std::size_t kDenseUpToBytes = 1u << 20;
  // 2% relative RMS error of the indirect light on the worst evaluation
  // light: well below what a viewer notices in smooth indirect light, and
  // what ours reaches on our scenes within kDefaultSizeLimit.
  static constexpr double kDefaultErrorBudget = 0.02;
  // 1/8 of dense float32 RGB: compression that saves less than that is not
  // worth its error next to the exact matrix.
  static constexpr double kDefaultSizeLimit = 0.125;

  // Fills unset values from the scene's bake block, then the defaults, so
  // every optional above except the grid choice has a value afterwards.
  void apply_scene_defaults(const BakeDefaults& defaults);
  // Throws InvalidSetting naming the setting for absurd values: each value
  // against its row's range (settings_table.h), then the combinations.
  void validate() const;
};

std::string to_string(PatchMode mode);
const char* to_string(CodecChoice codec);
const char* to_string(OutOfCore mode);
const char* to_string(ProbePlacementMode mode);

}  // namespace bounce
