#include "dynamic/temporal_radiosity_cl.h"

#include <algorithm>
#include <mutex>

#include "base/error.h"
#include "compute/kernel_source.h"
#include "compute/opencl_context.h"

namespace bounce {

struct ClTemporalRadiosity::Impl {
  OpenClContext& cl;
  std::size_t n = 0;
  TemporalSettings settings;
  std::uint32_t frame = 0;
  cl_kernel kernel = nullptr;
  std::vector<cl_mem> buffers;  // every buffer, for release
  cl_mem b = nullptr, history = nullptr, b_new = nullptr;
  std::vector<float> staging;  // 4 floats per patch

  explicit Impl(OpenClContext& context) : cl(context) {}
  ~Impl() {
    for (cl_mem m : buffers) clReleaseMemObject(m);
    if (kernel) clReleaseKernel(kernel);
  }
  cl_mem buffer(cl_mem_flags flags, std::size_t bytes, const void* data) {
    cl_int status = CL_SUCCESS;
    cl_mem m = clCreateBuffer(cl.context(), flags | (data ? CL_MEM_COPY_HOST_PTR : 0),
                              std::max<std::size_t>(bytes, 4), const_cast<void*>(data), &status);
    check_cl(status, "clCreateBuffer");
    buffers.push_back(m);
    return m;
  }
  void read(cl_mem from, std::vector<glm::vec3>& out) {
    std::lock_guard lock(cl.queue_mutex());
    check_cl(clEnqueueReadBuffer(cl.queue(), from, CL_TRUE, 0, staging.size() * sizeof(float),
                                 staging.data(), 0, nullptr, nullptr),
             "clEnqueueReadBuffer (temporal radiosity)");
    out.resize(n);
    for (std::size_t p = 0; p < n; ++p)
      out[p] = glm::vec3(staging[4 * p], staging[4 * p + 1], staging[4 * p + 2]);
  }
};

ClTemporalRadiosity::ClTemporalRadiosity(const TemporalRadiosity& cpu)
    : impl_(std::make_unique<Impl>(OpenClContext::shared())) {
  Impl& d = *impl_;
  d.n = cpu.size();
  d.settings = cpu.settings();
  const std::vector<AliasTables>& tables = cpu.tables();
  // Channel-major concatenation: row (c, p) starts at (c n + p) n.
  std::vector<AliasEntry> entries;
  std::vector<float> row_sum;
  for (const AliasTables& t : tables) {
    entries.insert(entries.end(), t.entries.begin(), t.entries.end());
    row_sum.insert(row_sum.end(), t.row_sum.begin(), t.row_sum.end());
  }
  cl_program program = d.cl.program("kernels/temporal_radiosity.cl",
                                    kernel_source("temporal_radiosity"), "-cl-std=CL1.2");
  cl_int status = CL_SUCCESS;
  d.kernel = clCreateKernel(program, "temporal_radiosity", &status);
  check_cl(status, "clCreateKernel (temporal_radiosity)");
  cl_mem table_mem =
      d.buffer(CL_MEM_READ_ONLY, entries.size() * sizeof(AliasEntry), entries.data());
  cl_mem sum_mem = d.buffer(CL_MEM_READ_ONLY, row_sum.size() * sizeof(float), row_sum.data());
  d.staging.assign(4 * d.n, 0.0f);
  const std::size_t vector_bytes = d.staging.size() * sizeof(float);
  d.b = d.buffer(CL_MEM_READ_ONLY, vector_bytes, nullptr);
  d.history = d.buffer(CL_MEM_READ_WRITE, vector_bytes, d.staging.data());
  d.b_new = d.buffer(CL_MEM_WRITE_ONLY, vector_bytes, nullptr);

  const auto n32 = static_cast<cl_uint>(d.n);
  const auto channels = static_cast<cl_uint>(tables.size());
  const std::array<int, 3>& map = cpu.channel_of_rgb();
  const cl_int colour[3] = {map[0], map[1], map[2]};
  const auto samples = static_cast<cl_uint>(d.settings.samples_per_patch);
  const cl_uint seed = d.settings.seed;
  check_cl(clSetKernelArg(d.kernel, 0, sizeof n32, &n32), "clSetKernelArg");
  check_cl(clSetKernelArg(d.kernel, 1, sizeof channels, &channels), "clSetKernelArg");
  for (cl_uint k = 0; k < 3; ++k)
    check_cl(clSetKernelArg(d.kernel, 2 + k, sizeof(cl_int), &colour[k]), "clSetKernelArg");
  check_cl(clSetKernelArg(d.kernel, 5, sizeof samples, &samples), "clSetKernelArg");
  check_cl(clSetKernelArg(d.kernel, 6, sizeof seed, &seed), "clSetKernelArg");
  const cl_mem mems[] = {table_mem, sum_mem, d.b, d.history, d.b_new};
  for (cl_uint a = 0; a < 5; ++a)
    check_cl(clSetKernelArg(d.kernel, 9 + a, sizeof(cl_mem), &mems[a]), "clSetKernelArg");
}

ClTemporalRadiosity::~ClTemporalRadiosity() = default;

void ClTemporalRadiosity::step(const std::vector<glm::vec3>& b) {
  Impl& d = *impl_;
  if (b.size() != d.n)
    throw Error(
        "temporal radiosity (OpenCL)",
        "b has " + std::to_string(b.size()) + " entries for " + std::to_string(d.n) + " patches");
  for (std::size_t p = 0; p < d.n; ++p) {
    d.staging[4 * p] = b[p].x;
    d.staging[4 * p + 1] = b[p].y;
    d.staging[4 * p + 2] = b[p].z;
    d.staging[4 * p + 3] = 0.0f;
  }
  const cl_uint frame = d.frame;
  const cl_float weight = temporal_blend_weight(d.settings.history_weight, d.frame);
  std::lock_guard lock(d.cl.queue_mutex());
  cl_command_queue queue = d.cl.queue();
  try {
    check_cl(clSetKernelArg(d.kernel, 7, sizeof frame, &frame), "clSetKernelArg (frame)");
    check_cl(clSetKernelArg(d.kernel, 8, sizeof weight, &weight), "clSetKernelArg (weight)");
    check_cl(clEnqueueWriteBuffer(queue, d.b, CL_FALSE, 0, d.staging.size() * sizeof(float),
                                  d.staging.data(), 0, nullptr, nullptr),
             "clEnqueueWriteBuffer (b)");
    const std::size_t global = std::max<std::size_t>(d.n, 1);
    check_cl(
        clEnqueueNDRangeKernel(queue, d.kernel, 1, nullptr, &global, nullptr, 0, nullptr, nullptr),
        "clEnqueueNDRangeKernel (temporal_radiosity)");
    check_cl(clFinish(queue), "clFinish (temporal_radiosity)");
  } catch (...) {
    clFinish(queue);  // the write may still read the staging buffer
    throw;
  }
  ++d.frame;
}

void ClTemporalRadiosity::reset() {
  Impl& d = *impl_;
  std::fill(d.staging.begin(), d.staging.end(), 0.0f);
  std::lock_guard lock(d.cl.queue_mutex());
  check_cl(
      clEnqueueWriteBuffer(d.cl.queue(), d.history, CL_TRUE, 0, d.staging.size() * sizeof(float),
                           d.staging.data(), 0, nullptr, nullptr),
      "clEnqueueWriteBuffer (history)");
  d.frame = 0;
}

std::uint32_t ClTemporalRadiosity::frame() const { return impl_->frame; }
void ClTemporalRadiosity::read_history(std::vector<glm::vec3>& history) const {
  impl_->read(impl_->history, history);
}
void ClTemporalRadiosity::read_estimate(std::vector<glm::vec3>& b_new) const {
  impl_->read(impl_->b_new, b_new);
}
const std::string& ClTemporalRadiosity::device_name() const { return impl_->cl.device_name(); }

}  // namespace bounce
