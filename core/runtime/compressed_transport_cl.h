#pragma once
// The run-time product of the compressed multi-bounce matrix on the OpenCL
// device (compute/opencl_context.h: the first GPU, else PoCL's CPU device
// here), kernel kernels/compressed_transport.cl. Same semantics as
// CompressedTransport (runtime/compressed_transport.h):
//   indirect_k = T~_c(k) b_k.
// The tables (blocks, palettes, corrections) are uploaded once at
// construction and stay on the device; the kernel reads the 8-byte blocks
// and decodes every texel's index itself. A product uploads b (gathered to
// stored order on the host), runs one kernel and reads the rows back: all
// device buffers and host staging are created at construction, none per call.
#include <array>
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "compress/codec.h"
#include "compress/compressed_transport_tables.h"

namespace bounce {

class ClCompressedTransport {
 public:
  // Throws bounce::Error when OpenCL has no device (OpenClError on any
  // OpenCL failure), or the errors of build_compressed_transport_tables.
  explicit ClCompressedTransport(const CompressedMatrix& m,
                                 const std::array<int, 3>& channel_of_rgb = {0, 1, 2});
  explicit ClCompressedTransport(const CompressedTransportTables& tables);
  ~ClCompressedTransport();
  ClCompressedTransport(const ClCompressedTransport&) = delete;
  ClCompressedTransport& operator=(const ClCompressedTransport&) = delete;

  // As CompressedTransport::multiply. Thread-safe (calls are serialised on
  // the shared queue).
  void multiply(const std::vector<glm::vec3>& b, std::vector<glm::vec3>& indirect) const;
  void multiply(std::span<const glm::vec3> b, std::span<glm::vec3> indirect) const;

  std::size_t size() const;
  const std::string& device_name() const;
  std::size_t work_group_size() const;
  // Bytes one product reads on the device (tables plus b), as for the C++ path.
  std::size_t bytes_per_product() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bounce
