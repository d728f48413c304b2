#pragma once
// `bounce bench dynamic`: the dynamic variants (temporal radiosity, the
// local-matrix update, the frame graph's aliased transients) against what
// they replace, on one bake, in one process (timings here swing by tens of
// percent between runs: compare within one run).
//  * per frame: the full multi-bounce product (dense
//    sgemv, the reference), temporal radiosity in C++ and on OpenCL, temporal
//    radiosity run through the frame graph with aliased transients, and the
//    classic K iterations on F; ms per frame, the area-weighted relative RMS
//    error against the full product after 1, 4, 16 and 64 frames, the
//    ghosting time after the light jumps, and memory (persistent and
//    transient); given a renderer, also SSIM and relative RMSE of the scene
//    camera's indirect picture against the full product's after 1, 4, 16
//    and 64 frames, and, given the path-traced reference, each method's
//    picture after 64 frames of the scene's own lights against it;
//  * the local matrix: removing and adding one patch by the rank-1 update
//    against recomputing T by LU;
//  * transient memory with and without aliasing for the bake's patch count
//    and three published scene sizes (1736, 262267 and 871414 polygons).
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "dynamic/light_temporal_radiosity.h"
#include "dynamic/temporal_radiosity.h"
#include "io/exr_writer.h"
#include "runtime/compressed_transport.h"

namespace bounce {

struct DynamicBenchInput {
  std::size_t n = 0;
  std::vector<const float*> transport;  // stored channels of T (K = the bake's)
  std::array<int, 3> channel_of_rgb{0, 1, 2};
  const float* form_factors = nullptr;  // F (n x n) or null: no classic, no local rows
  std::vector<glm::vec3> albedo;
  int classic_bounces = 16;
  std::vector<float> area;                     // patch areas, the error weights
  std::vector<glm::vec3> light, jumped_light;  // b before and after the jump

  // Optional image measures. render_indirect: the scene camera's indirect
  // picture of per-patch indirect light T b (as `bounce solve` renders it);
  // image_mask: the pixels to compare (1 = geometry).
  std::function<RgbFloatImage(const std::vector<glm::vec3>& indirect)> render_indirect;
  std::vector<std::uint8_t> image_mask;
  // Optional, with render_indirect: b of the scene's own lights and the
  // path-traced reference of the indirect picture under them (mean and
  // variance of the mean per pixel).
  std::vector<glm::vec3> scene_light;
  RgbFloatImage reference_indirect, reference_variance;
  int reference_frames = 64;  // frames of scene_light before the comparison

  // Optional: the bake's compressed matrix as the runtime multiplies it.
  // Adds the compressed product (the baseline a light update must beat) and
  // temporal radiosity with importance on the light, read from its tables.
  const CompressedTransport* compressed = nullptr;
  // Optional: b of a moving light, one per frame; every method runs the
  // path once (timed per frame, error against the full product of each
  // frame's light).
  std::vector<std::vector<glm::vec3>> moving_light;
};

struct DynamicBenchSettings {
  TemporalSettings temporal;
  LightTemporalSettings light_temporal;
  int repeats = 10;           // timed frames (after one warm-up)
  int ghosting_limit = 1000;  // frames searched for the end of ghosting
  bool local_matrix = true;   // time the LU recomputation (seconds for big n)
  bool classic = true;        // the classic row (K sgemv on F per frame: slow)
};

struct DynamicMethodRow {
  std::string method;
  bool available = true;
  std::string note;               // why unavailable, or what the row means
  double ms_per_frame = 0.0;      // best of the repeats
  std::array<double, 4> error{};  // after 1, 4, 16, 64 frames
  int ghosting_frames = 0;        // -1: not ended within the limit
  std::size_t persistent_bytes = 0, transient_bytes = 0;
  std::size_t bytes_per_frame = 0;  // what one frame reads (matrix or tables, b)
  // With moving_light: mean ms per frame along the path, the mean over its
  // frames of the patch error against that frame's full product, and the
  // last frame's picture SSIM against the full product's.
  bool moving = false;
  double moving_ms = 0.0, moving_error = 0.0, moving_ssim = 0.0;
  // With render_indirect: the picture 1 and 4 frames after the light
  // jumped, SSIM against the full product's of the new light (ghosting).
  std::array<double, 2> jump_ssim{};
  // With render_indirect: the camera's indirect picture after 1, 4, 16, 64
  // frames against the full product's (mean SSIM, relative RMSE).
  bool images = false;
  std::array<double, 4> image_ssim{}, image_error{};
  // With the reference: after reference_frames frames of the scene's
  // lights, noise-corrected relative RMSE and SSIM against the path tracer.
  bool against_reference = false;
  double reference_error = 0.0, reference_ssim = 0.0;
};

struct LocalMatrixRow {
  std::size_t patch = 0;
  double sigma = 0.0;
  double remove_ms = 0.0, add_ms = 0.0, recompute_ms = 0.0;
  double remove_vs_recompute = 0.0;  // max |T_update - T_LU| / max |T|
  double round_trip = 0.0;           // remove then add, against the original
};

struct TransientMemoryRow {
  std::string scene;
  std::size_t patches = 0;
  std::size_t unaliased_bytes = 0, aliased_bytes = 0;
};

struct DynamicBench {
  std::size_t n = 0;
  std::vector<DynamicMethodRow> methods;
  std::vector<LocalMatrixRow> local;
  std::vector<TransientMemoryRow> memory;
  double ghosting_threshold = 0.0;        // the error level that ends ghosting
  int image_width = 0, image_height = 0;  // 0: no image measures
  double reference_noise = 0.0;           // the reference's own relative noise
};

DynamicBench run_dynamic_bench(const DynamicBenchInput& in, const DynamicBenchSettings& settings);

// The compressed product of a compressed matrix as the runtime multiplies
// it (the block loop the CPU has), for DynamicBenchInput::compressed; null
// when there is none (a bake stored dense). channel_of_rgb: the stored
// channel of R, G and B.
std::unique_ptr<CompressedTransport> compressed_product(
    const std::optional<CompressedMatrix>& matrix, const std::array<int, 3>& channel_of_rgb);

// Area-weighted relative RMS over patches and colours: sqrt(sum A |y - y*|^2
// / sum A |y*|^2).
double relative_rms(const std::vector<glm::vec3>& y, const std::vector<glm::vec3>& exact,
                    const std::vector<float>& area);

std::string dynamic_bench_table(const DynamicBench& bench);

}  // namespace bounce
