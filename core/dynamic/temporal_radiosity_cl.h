#pragma once
// Temporal radiosity (dynamic/temporal_radiosity.h) on the OpenCL device
// (compute/opencl_context.h: the first GPU, else PoCL's CPU device here),
// kernel kernels/temporal_radiosity.cl. The alias tables are uploaded once;
// the history stays on the device between frames (one buffer, blended in
// place), a frame uploads b and runs one kernel; the history and the
// frame's estimate are read back on request.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "dynamic/temporal_radiosity.h"

namespace bounce {

class ClTemporalRadiosity {
 public:
  // Uploads the tables of `cpu` (same settings, same random stream). Throws
  // bounce::Error (OpenClError) when OpenCL has no device or fails.
  explicit ClTemporalRadiosity(const TemporalRadiosity& cpu);
  ~ClTemporalRadiosity();
  ClTemporalRadiosity(const ClTemporalRadiosity&) = delete;
  ClTemporalRadiosity& operator=(const ClTemporalRadiosity&) = delete;

  // One frame with this object's counter (as TemporalRadiosity::step):
  // estimate, blend into the device history, advance. Waits for the kernel.
  void step(const std::vector<glm::vec3>& b);
  // Sets the device history to zero and the frame counter to 0.
  void reset();
  std::uint32_t frame() const;
  void read_history(std::vector<glm::vec3>& history) const;
  void read_estimate(std::vector<glm::vec3>& b_new) const;  // the last frame's B_new
  const std::string& device_name() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bounce
