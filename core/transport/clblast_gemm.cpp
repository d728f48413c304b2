#include "transport/clblast_gemm.h"

// OpenCL 1.2 is what every driver offers (PoCL, Mesa, the GPU vendors'); with
// it clCreateCommandQueue is not deprecated and nothing newer is needed.
#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <clblast.h>

#include <mutex>
#include <vector>

#include "compute/opencl_context.h"

namespace bounce {

namespace {

// The one place OpenCL and CLBlast statuses become exceptions.
void check(cl_int status, const char* call) {
  if (status != CL_SUCCESS) throw OpenClError(call, status);
}
void check(clblast::StatusCode status, const char* call) {
  if (status != clblast::StatusCode::kSuccess) throw OpenClError(call, static_cast<int>(status));
}

// CLBlast runs on Bounce's shared OpenCL context and queue (one device
// selection for the process); its compiled kernels are cached per context, so
// one long-lived context also means they are compiled once. Its A, B, C
// buffers are its own.
struct GemmBuffers {
  std::mutex mutex;             // the buffers are reused product after product
  std::vector<cl_mem> buffers;  // A, B, C, each `capacity` floats
  std::size_t capacity = 0;

  void reserve(cl_context context, std::size_t floats) {
    if (floats <= capacity) return;
    for (cl_mem b : buffers) clReleaseMemObject(b);
    buffers.clear();
    capacity = 0;
    for (int i = 0; i < 3; ++i) {
      cl_int status = CL_SUCCESS;
      buffers.push_back(
          clCreateBuffer(context, CL_MEM_READ_WRITE, floats * sizeof(float), nullptr, &status));
      check(status, "clCreateBuffer");
    }
    capacity = floats;
  }
};

// Never destroyed, like the context it lives in.
GemmBuffers& shared_buffers() {
  static GemmBuffers* buffers = new GemmBuffers();
  return *buffers;
}

}  // namespace

struct ClblastGemm::Impl {
  OpenClContext& cl;
  GemmBuffers& gemm;
};

ClblastGemm::ClblastGemm()
    : impl_(std::make_unique<Impl>(Impl{OpenClContext::shared(), shared_buffers()})) {}
ClblastGemm::~ClblastGemm() = default;

std::string ClblastGemm::name() const { return "CLBlast (" + impl_->cl.device_name() + ")"; }
const std::string& ClblastGemm::device_name() const { return impl_->cl.device_name(); }

void ClblastGemm::multiply(std::size_t n, const float* a, const float* b, float beta, float* c) {
  if (n == 0) return;
  OpenClContext& cl = impl_->cl;
  GemmBuffers& d = impl_->gemm;
  // Buffers first, then the queue: every user of the shared queue takes only
  // the queue lock, so the order cannot deadlock.
  std::lock_guard buffers_lock(d.mutex);
  std::lock_guard queue_lock(cl.queue_mutex());
  const std::size_t bytes = n * n * sizeof(float);
  d.reserve(cl.context(), n * n);
  cl_command_queue queue = cl.queue();
  try {
    // Non-blocking uploads are safe: the queue is in order and the blocking
    // read at the end returns only after everything before it has run.
    check(clEnqueueWriteBuffer(queue, d.buffers[0], CL_FALSE, 0, bytes, a, 0, nullptr, nullptr),
          "clEnqueueWriteBuffer");
    check(clEnqueueWriteBuffer(queue, d.buffers[1], CL_FALSE, 0, bytes, b, 0, nullptr, nullptr),
          "clEnqueueWriteBuffer");
    if (beta != 0.0f)
      check(clEnqueueWriteBuffer(queue, d.buffers[2], CL_FALSE, 0, bytes, c, 0, nullptr, nullptr),
            "clEnqueueWriteBuffer");
    check(clblast::Gemm<float>(clblast::Layout::kRowMajor, clblast::Transpose::kNo,
                               clblast::Transpose::kNo, n, n, n, 1.0f, d.buffers[0], 0, n,
                               d.buffers[1], 0, n, beta, d.buffers[2], 0, n, &queue),
          "clblast::Gemm");
    check(clEnqueueReadBuffer(queue, d.buffers[2], CL_TRUE, 0, bytes, c, 0, nullptr, nullptr),
          "clEnqueueReadBuffer");
  } catch (...) {
    // Pending uploads read the caller's memory: let them finish before the
    // exception unwinds past its owner.
    clFinish(queue);
    throw;
  }
}

}  // namespace bounce
