#pragma once
// `bounce bench dynamic`: the dynamic variants of paper 003 against what
// they replace, on one bake, in one process (timings here swing by tens of
// percent between runs: compare within one run).
//  * per frame (the paper's Table 2): the full multi-bounce product (dense
//    sgemv, the reference), temporal radiosity in C++ and on OpenCL, temporal
//    radiosity run through the frame graph with aliased transients, and the
//    classic K iterations on F; ms per frame, the area-weighted relative RMS
//    error against the full product after 1, 4, 16 and 64 frames, the
//    ghosting time after the light jumps, and memory (persistent and
//    transient);
//  * the local matrix: removing and adding one patch by the rank-1 update
//    against recomputing T by LU;
//  * transient memory with and without aliasing (the paper's Table 1) for
//    the bake's patch count and the paper's scene sizes.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "dynamic/temporal_radiosity.h"

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
};

struct DynamicBenchSettings {
  TemporalSettings temporal;
  int repeats = 10;           // timed frames (after one warm-up)
  int ghosting_limit = 1000;  // frames searched for the end of ghosting
  bool local_matrix = true;   // time the LU recomputation (seconds for big n)
};

struct DynamicMethodRow {
  std::string method;
  bool available = true;
  std::string note;               // why unavailable, or what the row means
  double ms_per_frame = 0.0;      // best of the repeats
  std::array<double, 4> error{};  // after 1, 4, 16, 64 frames
  int ghosting_frames = 0;        // -1: not ended within the limit
  std::size_t persistent_bytes = 0, transient_bytes = 0;
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
  double ghosting_threshold = 0.0;  // the error level that ends ghosting
};

DynamicBench run_dynamic_bench(const DynamicBenchInput& in, const DynamicBenchSettings& settings);

// Area-weighted relative RMS over patches and colours: sqrt(sum A |y - y*|^2
// / sum A |y*|^2).
double relative_rms(const std::vector<glm::vec3>& y, const std::vector<glm::vec3>& exact,
                    const std::vector<float>& area);

std::string dynamic_bench_table(const DynamicBench& bench);

}  // namespace bounce
