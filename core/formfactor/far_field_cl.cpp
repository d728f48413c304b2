#include "formfactor/far_field_cl.h"

#include <limits>
#include <mutex>
#include <vector>

#include <glm/glm.hpp>

#include "base/error.h"
#include "compute/kernel_source.h"
#include "compute/opencl_context.h"

namespace bounce {

namespace {

// A work-group of 16 x 16 pairs: a common size on GPUs; PoCL's CPU device
// runs a work-group as one loop, so the size only has to be big enough for
// its vectoriser. The range is rounded up to it.
constexpr std::size_t kTile = 16;

std::size_t round_up(std::size_t x, std::size_t to) { return (x + to - 1) / to * to; }

// Releases what a call created, whichever way it leaves.
struct Resources {
  std::vector<cl_mem> buffers;
  cl_kernel kernel = nullptr;
  ~Resources() {
    for (cl_mem m : buffers) clReleaseMemObject(m);
    if (kernel) clReleaseKernel(kernel);
  }

  cl_mem buffer(cl_context context, cl_mem_flags flags, std::size_t bytes, const void* data) {
    cl_int status = CL_SUCCESS;
    // A zero-sized buffer is an error in OpenCL; the kernel never reads it then.
    cl_mem m = clCreateBuffer(context, flags, bytes ? bytes : 4,
                              data ? const_cast<void*>(data) : nullptr, &status);
    check_cl(status, "clCreateBuffer");
    buffers.push_back(m);
    return m;
  }
};

}  // namespace

std::string far_field_device_name() { return OpenClContext::shared().device_name(); }

std::vector<float> far_field_sums_cl(const FarPoints& points) {
  validate(points);
  const std::size_t n = points.patches();
  std::vector<float> sums(n * n, 0.0f);
  if (n == 0) return sums;
  if (n > std::numeric_limits<cl_uint>::max() ||
      points.offsets.back() > std::numeric_limits<cl_uint>::max() / 3)
    throw Error("far field (OpenCL)", "too many patches or points");
  OpenClContext& cl = OpenClContext::shared();
  cl_program program =
      cl.program("kernels/far_field.cl", kernel_source("far_field"), "-cl-std=CL1.2");
  Resources r;
  cl_int status = CL_SUCCESS;
  r.kernel = clCreateKernel(program, "far_field", &status);
  check_cl(status, "clCreateKernel (far_field)");

  // glm::vec3 is three packed floats: the kernel's vload3 layout as it is.
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  const std::size_t m = points.offsets.back();
  const cl_mem_flags in = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
  const cl_mem positions =
      r.buffer(cl.context(), in, m * sizeof(glm::vec3), m ? points.positions.data() : nullptr);
  const cl_mem normals =
      r.buffer(cl.context(), in, m * sizeof(glm::vec3), m ? points.normals.data() : nullptr);
  const cl_mem areas =
      r.buffer(cl.context(), in, m * sizeof(float), m ? points.areas.data() : nullptr);
  const cl_mem offsets =
      r.buffer(cl.context(), in, (n + 1) * sizeof(cl_uint), points.offsets.data());
  const cl_mem out = r.buffer(cl.context(), CL_MEM_WRITE_ONLY, n * n * sizeof(float), nullptr);

  const auto count = static_cast<cl_uint>(n);
  check_cl(clSetKernelArg(r.kernel, 0, sizeof count, &count), "clSetKernelArg");
  const cl_mem args[] = {positions, normals, areas, offsets, out};
  for (cl_uint a = 0; a < 5; ++a)
    check_cl(clSetKernelArg(r.kernel, a + 1, sizeof(cl_mem), &args[a]), "clSetKernelArg");

  // A device that cannot run a whole tile picks its own work-group size.
  std::size_t kernel_max = 0;
  check_cl(clGetKernelWorkGroupInfo(r.kernel, cl.device(), CL_KERNEL_WORK_GROUP_SIZE,
                                    sizeof kernel_max, &kernel_max, nullptr),
           "clGetKernelWorkGroupInfo");
  const bool tiled = kernel_max >= kTile * kTile;
  const std::size_t global[2] = {round_up(n, kTile), round_up(n, kTile)};
  const std::size_t local[2] = {kTile, kTile};
  std::lock_guard lock(cl.queue_mutex());
  check_cl(clEnqueueNDRangeKernel(cl.queue(), r.kernel, 2, nullptr, global, tiled ? local : nullptr,
                                  0, nullptr, nullptr),
           "clEnqueueNDRangeKernel (far_field)");
  check_cl(clEnqueueReadBuffer(cl.queue(), out, CL_TRUE, 0, n * n * sizeof(float), sums.data(), 0,
                               nullptr, nullptr),
           "clEnqueueReadBuffer (far field sums)");
  return sums;
}

}  // namespace bounce
