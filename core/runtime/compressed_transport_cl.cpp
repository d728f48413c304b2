#include "runtime/compressed_transport_cl.h"

#include <algorithm>
#include <mutex>
#include <string>

#include "base/error.h"
#include "compute/kernel_source.h"
#include "compute/opencl_context.h"

namespace bounce {

namespace {

// Work-items per block row: a common GPU work-group size; on PoCL's CPU
// device 128 to 512 measured alike (64 slower, 1024 no better), and small
// matrices take fewer (at most one per block column). A power of two: the
// kernel's reduction halves it.
constexpr std::size_t kMaxWorkGroup = 128;

std::size_t floor_pow2(std::size_t x) {
  std::size_t p = 1;
  while (p * 2 <= x) p *= 2;
  return p;
}

std::string build_options(const CompressedTransportTables& t) {
  std::string o = "-cl-std=CL1.2";
  const auto define = [&o](const char* name, int value) {
    o += std::string(" -D") + name + "=" + std::to_string(value);
  };
  define("BC4", t.format == DdsFormat::kBc4 ? 1 : 0);
  define("RGB_PALETTE", t.slots == 3 ? 1 : 0);
  define("CORRECTION_WIDTH", t.correction_width);
  return o;
}

// The palettes as the kernel reads them, one per block (the C++ path looks
// BC1 palettes up in the slot tables instead; on a GPU the tables would sit
// in local memory, on PoCL per-block palettes measured no slower): with
// three slots, entry-major with the colours' mapping applied, (R, G, B, 0)
// per entry, so a texel is one float4 load; with one slot, as they are.
std::vector<float> device_palettes(const CompressedTransportTables& t) {
  if (t.format == DdsFormat::kBc4) return t.palettes;
  const std::size_t nb = t.block_rows, levels = 4;
  const std::size_t width = t.slots == 3 ? 4 : 1;
  std::vector<float> out(nb * nb * levels * width, 0.0f);
  for (std::size_t I = 0; I < nb; ++I)
    for (std::size_t J = 0; J < nb; ++J) {
      const std::size_t b = I * nb + J;
      for (std::size_t k = 0; k < (t.slots == 3 ? 3u : 1u); ++k) {
        const float* palette = t.palette(I, J, t.slots == 3 ? t.slot_of_colour[k] : 0);
        for (std::size_t e = 0; e < levels; ++e) out[(b * levels + e) * width + k] = palette[e];
      }
    }
  return out;
}

}  // namespace

struct ClCompressedTransport::Impl {
  OpenClContext& cl;
  std::size_t n = 0, padded = 0, block_rows = 0, table_bytes = 0;
  Permutation permutation;
  cl_kernel kernel = nullptr;
  std::vector<cl_mem> buffers;      // every buffer, for release
  cl_mem b = nullptr, y = nullptr;  // per product: b in, rows out (float4 per stored row)
  std::size_t work_group = 1;
  mutable std::vector<float> b_staging, y_staging;  // 4 floats per stored row

  explicit Impl(OpenClContext& context) : cl(context) {}
  ~Impl() {
    for (cl_mem m : buffers) clReleaseMemObject(m);
    if (kernel) clReleaseKernel(kernel);
  }

  template <class T>
  cl_mem upload(const std::vector<T>& data) {
    // OpenCL has no empty buffers: an empty table gets one unused element.
    const std::size_t bytes = std::max<std::size_t>(data.size(), 1) * sizeof(T);
    const T none{};
    cl_int status = CL_SUCCESS;
    cl_mem m = clCreateBuffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes,
                              const_cast<T*>(data.empty() ? &none : data.data()), &status);
    check_cl(status, "clCreateBuffer");
    buffers.push_back(m);
    return m;
  }
  cl_mem device_buffer(cl_mem_flags flags, std::size_t bytes) {
    cl_int status = CL_SUCCESS;
    cl_mem m = clCreateBuffer(cl.context(), flags, bytes, nullptr, &status);
    check_cl(status, "clCreateBuffer");
    buffers.push_back(m);
    return m;
  }
};

ClCompressedTransport::ClCompressedTransport(const CompressedMatrix& m,
                                             const std::array<int, 3>& channel_of_rgb)
    : ClCompressedTransport(build_compressed_transport_tables(m, channel_of_rgb)) {}

ClCompressedTransport::ClCompressedTransport(const CompressedTransportTables& t)
    : impl_(std::make_unique<Impl>(OpenClContext::shared())) {
  Impl& d = *impl_;
  d.n = t.n;
  d.padded = t.padded;
  d.block_rows = t.block_rows;
  const std::vector<float> palettes_on_device = device_palettes(t);
  // What a product reads on the device: the tables with its palette layout.
  d.table_bytes = t.bytes() + palettes_on_device.size() * sizeof(float) -
                  (t.palettes.size() + t.bc1_tables.size()) * sizeof(float);
  d.permutation = t.permutation;
  if (t.block_rows > 0xFFFFFFFFu) throw Error("compressed transport", "too many block columns");
  cl_program program = d.cl.program("kernels/compressed_transport.cl",
                                    kernel_source("compressed_transport"), build_options(t));
  cl_int status = CL_SUCCESS;
  d.kernel = clCreateKernel(program, "compressed_transport", &status);
  check_cl(status, "clCreateKernel (compressed_transport)");

  std::size_t kernel_max = 0, device_max = 0;
  check_cl(clGetKernelWorkGroupInfo(d.kernel, d.cl.device(), CL_KERNEL_WORK_GROUP_SIZE,
                                    sizeof kernel_max, &kernel_max, nullptr),
           "clGetKernelWorkGroupInfo");
  check_cl(clGetDeviceInfo(d.cl.device(), CL_DEVICE_MAX_WORK_GROUP_SIZE, sizeof device_max,
                           &device_max, nullptr),
           "clGetDeviceInfo");
  d.work_group = floor_pow2(
      std::max<std::size_t>(1, std::min({kMaxWorkGroup, kernel_max, device_max, t.block_rows})));

  cl_mem blocks = d.upload(t.blocks);
  cl_mem palettes = d.upload(palettes_on_device);
  cl_mem ptr = d.upload(t.correction_ptr);
  cl_mem index = d.upload(t.correction_index);
  cl_mem value = d.upload(t.correction_value);
  const std::size_t vector_bytes = std::max<std::size_t>(t.padded, 1) * 4 * sizeof(float);
  d.b = d.device_buffer(CL_MEM_READ_ONLY, vector_bytes);
  d.y = d.device_buffer(CL_MEM_WRITE_ONLY, vector_bytes);
  // Padding rows of b stay 0 in the staging buffer, so padding columns add 0.
  d.b_staging.assign(4 * t.padded, 0.0f);
  d.y_staging.assign(4 * t.padded, 0.0f);

  const cl_uint block_cols = static_cast<cl_uint>(t.block_rows);
  cl_mem args[] = {blocks, palettes, ptr, index, value, d.b, d.y};
  check_cl(clSetKernelArg(d.kernel, 0, sizeof block_cols, &block_cols), "clSetKernelArg");
  for (cl_uint a = 0; a < 7; ++a)
    check_cl(clSetKernelArg(d.kernel, a + 1, sizeof(cl_mem), &args[a]), "clSetKernelArg");
  check_cl(clSetKernelArg(d.kernel, 8, 4 * sizeof(float) * 4 * d.work_group, nullptr),
           "clSetKernelArg (local scratch)");
}

ClCompressedTransport::~ClCompressedTransport() = default;

std::size_t ClCompressedTransport::size() const { return impl_->n; }
const std::string& ClCompressedTransport::device_name() const { return impl_->cl.device_name(); }
std::size_t ClCompressedTransport::work_group_size() const { return impl_->work_group; }
std::size_t ClCompressedTransport::bytes_per_product() const {
  return impl_->table_bytes + impl_->n * sizeof(glm::vec3);
}

void ClCompressedTransport::multiply(const std::vector<glm::vec3>& b,
                                     std::vector<glm::vec3>& indirect) const {
  if (b.size() == impl_->n && indirect.size() != impl_->n) indirect.resize(impl_->n);
  multiply(std::span<const glm::vec3>(b), std::span<glm::vec3>(indirect));
}

void ClCompressedTransport::multiply(std::span<const glm::vec3> b,
                                     std::span<glm::vec3> indirect) const {
  const Impl& d = *impl_;
  if (b.size() != d.n)
    throw Error("compressed transport", "b has " + std::to_string(b.size()) + " entries for " +
                                            std::to_string(d.n) + " patches");
  if (indirect.size() != d.n)
    throw Error("compressed transport", "the output has " + std::to_string(indirect.size()) +
                                            " entries for " + std::to_string(d.n) + " patches");
  if (d.n == 0) return;
  std::lock_guard lock(d.cl.queue_mutex());
  for (std::size_t i = 0; i < d.n; ++i) {
    const glm::vec3& v = b[d.permutation[i]];
    d.b_staging[4 * i] = v.x;
    d.b_staging[4 * i + 1] = v.y;
    d.b_staging[4 * i + 2] = v.z;
  }
  const std::size_t bytes = d.b_staging.size() * sizeof(float);
  cl_command_queue queue = d.cl.queue();
  const std::size_t local = d.work_group, global = d.block_rows * local;
  try {
    check_cl(clEnqueueWriteBuffer(queue, d.b, CL_FALSE, 0, bytes, d.b_staging.data(), 0, nullptr,
                                  nullptr),
             "clEnqueueWriteBuffer (b)");
    check_cl(
        clEnqueueNDRangeKernel(queue, d.kernel, 1, nullptr, &global, &local, 0, nullptr, nullptr),
        "clEnqueueNDRangeKernel (compressed_transport)");
    check_cl(
        clEnqueueReadBuffer(queue, d.y, CL_TRUE, 0, bytes, d.y_staging.data(), 0, nullptr, nullptr),
        "clEnqueueReadBuffer (y)");
  } catch (...) {
    // Enqueued work may still read the staging buffers: let it finish.
    clFinish(queue);
    throw;
  }
  for (std::size_t i = 0; i < d.n; ++i)
    indirect[d.permutation[i]] =
        glm::vec3(d.y_staging[4 * i], d.y_staging[4 * i + 1], d.y_staging[4 * i + 2]);
}

}  // namespace bounce
