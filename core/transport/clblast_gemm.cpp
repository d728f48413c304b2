#include "transport/clblast_gemm.h"

// OpenCL 1.2 is what every driver offers (PoCL, Mesa, the GPU vendors'); with
// it clCreateCommandQueue is not deprecated and nothing newer is needed.
#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <clblast.h>

#include <mutex>
#include <vector>

namespace bounce {

namespace {

const char* status_name(int status) {
  switch (status) {
    case CL_DEVICE_NOT_FOUND: return "CL_DEVICE_NOT_FOUND";
    case CL_DEVICE_NOT_AVAILABLE: return "CL_DEVICE_NOT_AVAILABLE";
    case CL_COMPILER_NOT_AVAILABLE: return "CL_COMPILER_NOT_AVAILABLE";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE: return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_OUT_OF_RESOURCES: return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY: return "CL_OUT_OF_HOST_MEMORY";
    case CL_BUILD_PROGRAM_FAILURE: return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_VALUE: return "CL_INVALID_VALUE";
    case CL_INVALID_PLATFORM: return "CL_INVALID_PLATFORM";
    case CL_INVALID_DEVICE: return "CL_INVALID_DEVICE";
    case CL_INVALID_CONTEXT: return "CL_INVALID_CONTEXT";
    case CL_INVALID_COMMAND_QUEUE: return "CL_INVALID_COMMAND_QUEUE";
    case CL_INVALID_MEM_OBJECT: return "CL_INVALID_MEM_OBJECT";
    case CL_INVALID_BUFFER_SIZE: return "CL_INVALID_BUFFER_SIZE";
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR (no OpenCL driver installed)";
    case -2041: return "CLBlast kDatabaseError (no tuning entry for this device)";
    case -2046: return "CLBlast kInvalidLocalMemUsage";
    case -2040: return "CLBlast kUnknownError";
    case -2039: return "CLBlast kUnexpectedError";
    default: return nullptr;
  }
}

std::string describe(const std::string& call, int status) {
  const char* name = status_name(status);
  return call + " failed with status " + std::to_string(status) +
         (name ? std::string(" (") + name + ")" : std::string());
}

// The one place OpenCL and CLBlast statuses become exceptions.
void check(cl_int status, const char* call) {
  if (status != CL_SUCCESS) throw OpenClError(call, status);
}
void check(clblast::StatusCode status, const char* call) {
  if (status != clblast::StatusCode::kSuccess) throw OpenClError(call, static_cast<int>(status));
}

std::string device_string(cl_device_id device, cl_device_info what) {
  std::size_t size = 0;
  check(clGetDeviceInfo(device, what, 0, nullptr, &size), "clGetDeviceInfo");
  std::string s(size, '\0');
  check(clGetDeviceInfo(device, what, size, s.data(), nullptr), "clGetDeviceInfo");
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

// One OpenCL context and in-order queue per process. CLBlast caches its
// compiled kernels per context, and compiling them on PoCL takes seconds:
// a context per product would recompile every time. The object is never
// destroyed on purpose: releasing OpenCL objects from a static destructor
// races with the driver's own teardown at exit (a known PoCL crash).
struct OpenClDevice {
  cl_device_id device = nullptr;
  cl_context context = nullptr;
  cl_command_queue queue = nullptr;
  std::string name;
  std::mutex mutex;  // one product at a time on the shared queue and buffers
  std::vector<cl_mem> buffers;  // A, B, C, each `capacity` floats
  std::size_t capacity = 0;

  OpenClDevice() {
    cl_uint platform_count = 0;
    check(clGetPlatformIDs(0, nullptr, &platform_count), "clGetPlatformIDs");
    if (platform_count == 0) throw OpenClError("clGetPlatformIDs (no OpenCL platform)", -1001);
    std::vector<cl_platform_id> platforms(platform_count);
    check(clGetPlatformIDs(platform_count, platforms.data(), nullptr), "clGetPlatformIDs");
    cl_device_id first = nullptr, gpu = nullptr;
    for (cl_platform_id platform : platforms) {
      cl_uint count = 0;
      if (clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 0, nullptr, &count) != CL_SUCCESS) continue;
      std::vector<cl_device_id> devices(count);
      if (clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, count, devices.data(), nullptr) !=
          CL_SUCCESS)
        continue;
      for (cl_device_id d : devices) {
        if (!first) first = d;
        cl_device_type type = 0;
        if (!gpu && clGetDeviceInfo(d, CL_DEVICE_TYPE, sizeof(type), &type, nullptr) == CL_SUCCESS &&
            (type & CL_DEVICE_TYPE_GPU))
          gpu = d;
      }
    }
    device = gpu ? gpu : first;
    if (!device) throw OpenClError("clGetDeviceIDs (no OpenCL device on any platform)",
                                   CL_DEVICE_NOT_FOUND);
    name = device_string(device, CL_DEVICE_NAME);
    cl_int status = CL_SUCCESS;
    context = clCreateContext(nullptr, 1, &device, nullptr, nullptr, &status);
    check(status, "clCreateContext");
#if CL_TARGET_OPENCL_VERSION >= 200
    queue = clCreateCommandQueueWithProperties(context, device, nullptr, &status);
#else
    queue = clCreateCommandQueue(context, device, 0, &status);
#endif
    check(status, "clCreateCommandQueue");
  }

  void reserve(std::size_t floats) {
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

OpenClDevice& shared_device() {
  static std::mutex mutex;
  static OpenClDevice* device = nullptr;
  static std::string failure;
  std::lock_guard lock(mutex);
  if (device) return *device;
  // A missing driver does not appear later in the same process: remember the
  // first failure instead of probing the ICD loader again on every call.
  if (!failure.empty()) throw Error("OpenCL", failure);
  try {
    device = new OpenClDevice();
  } catch (const Error& e) {
    failure = e.what();
    throw;
  }
  return *device;
}

}  // namespace

OpenClError::OpenClError(const std::string& call, int status)
    : Error("OpenCL", describe(call, status)), status_(status) {}

struct ClblastGemm::Impl {
  OpenClDevice& device;
};

ClblastGemm::ClblastGemm() : impl_(std::make_unique<Impl>(Impl{shared_device()})) {}
ClblastGemm::~ClblastGemm() = default;

std::string ClblastGemm::name() const { return "CLBlast (" + impl_->device.name + ")"; }
const std::string& ClblastGemm::device_name() const { return impl_->device.name; }

void ClblastGemm::multiply(std::size_t n, const float* a, const float* b, float beta, float* c) {
  if (n == 0) return;
  OpenClDevice& d = impl_->device;
  std::lock_guard lock(d.mutex);
  const std::size_t bytes = n * n * sizeof(float);
  d.reserve(n * n);
  try {
    // Non-blocking uploads are safe: the queue is in order and the blocking
    // read at the end returns only after everything before it has run.
    check(clEnqueueWriteBuffer(d.queue, d.buffers[0], CL_FALSE, 0, bytes, a, 0, nullptr, nullptr),
          "clEnqueueWriteBuffer");
    check(clEnqueueWriteBuffer(d.queue, d.buffers[1], CL_FALSE, 0, bytes, b, 0, nullptr, nullptr),
          "clEnqueueWriteBuffer");
    if (beta != 0.0f)
      check(
          clEnqueueWriteBuffer(d.queue, d.buffers[2], CL_FALSE, 0, bytes, c, 0, nullptr, nullptr),
          "clEnqueueWriteBuffer");
    check(clblast::Gemm<float>(clblast::Layout::kRowMajor, clblast::Transpose::kNo,
                               clblast::Transpose::kNo, n, n, n, 1.0f, d.buffers[0], 0, n,
                               d.buffers[1], 0, n, beta, d.buffers[2], 0, n, &d.queue),
          "clblast::Gemm");
    check(clEnqueueReadBuffer(d.queue, d.buffers[2], CL_TRUE, 0, bytes, c, 0, nullptr, nullptr),
          "clEnqueueReadBuffer");
  } catch (...) {
    // Pending uploads read the caller's memory: let them finish before the
    // exception unwinds past its owner.
    clFinish(d.queue);
    throw;
  }
}

}  // namespace bounce
