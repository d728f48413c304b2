#include "compute/opencl_context.h"

#include <optional>
#include <vector>

namespace bounce {

namespace {

std::string device_string(cl_device_id device, cl_device_info what) {
  std::size_t size = 0;
  check_cl(clGetDeviceInfo(device, what, 0, nullptr, &size), "clGetDeviceInfo");
  std::string s(size, '\0');
  check_cl(clGetDeviceInfo(device, what, size, s.data(), nullptr), "clGetDeviceInfo");
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

std::string build_log(cl_program program, cl_device_id device) {
  std::size_t size = 0;
  if (clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size) != CL_SUCCESS)
    return "(no build log)";
  std::string log(size, '\0');
  if (clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr) !=
      CL_SUCCESS)
    return "(no build log)";
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

}  // namespace

void check_cl(cl_int status, const std::string& call) {
  if (status != CL_SUCCESS) throw OpenClError(call, status);
}

OpenClContext& OpenClContext::shared() {
  static std::mutex mutex;
  static OpenClContext* instance = nullptr;
  static std::optional<OpenClError> failure;
  std::lock_guard lock(mutex);
  if (instance) return *instance;
  // A missing driver does not appear later in the same process: remember the
  // first failure and throw it again (as the same type, which callers such
  // as the GEMM backend selection catch to fall back).
  if (failure) throw *failure;
  try {
    instance = new OpenClContext();
  } catch (const OpenClError& e) {
    failure = e;
    throw;
  }
  return *instance;
}

OpenClContext::OpenClContext() {
  cl_uint platform_count = 0;
  const cl_int found = clGetPlatformIDs(0, nullptr, &platform_count);
  // The ICD loader reports "no platform" as an error status, not as zero.
  if (found == -1001 /* CL_PLATFORM_NOT_FOUND_KHR */ || (found == CL_SUCCESS && !platform_count))
    throw OpenClError("clGetPlatformIDs (no OpenCL platform)", -1001);
  check_cl(found, "clGetPlatformIDs");
  std::vector<cl_platform_id> platforms(platform_count);
  check_cl(clGetPlatformIDs(platform_count, platforms.data(), nullptr), "clGetPlatformIDs");
  cl_device_id first = nullptr, gpu = nullptr;
  for (cl_platform_id platform : platforms) {
    cl_uint count = 0;
    // A platform without devices answers CL_DEVICE_NOT_FOUND: try the next.
    if (clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 0, nullptr, &count) != CL_SUCCESS) continue;
    std::vector<cl_device_id> devices(count);
    if (clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, count, devices.data(), nullptr) != CL_SUCCESS)
      continue;
    for (cl_device_id d : devices) {
      if (!first) first = d;
      cl_device_type type = 0;
      if (!gpu && clGetDeviceInfo(d, CL_DEVICE_TYPE, sizeof(type), &type, nullptr) == CL_SUCCESS &&
          (type & CL_DEVICE_TYPE_GPU))
        gpu = d;
    }
  }
  device_ = gpu ? gpu : first;
  if (!device_)
    throw OpenClError("clGetDeviceIDs (no OpenCL device on any platform)", CL_DEVICE_NOT_FOUND);
  device_name_ = device_string(device_, CL_DEVICE_NAME);
  cl_int status = CL_SUCCESS;
  context_ = clCreateContext(nullptr, 1, &device_, nullptr, nullptr, &status);
  check_cl(status, "clCreateContext");
  queue_ = clCreateCommandQueue(context_, device_, 0, &status);
  check_cl(status, "clCreateCommandQueue");
}

cl_program OpenClContext::program(const std::string& name, const std::string& source,
                                  const std::string& options) {
  std::lock_guard lock(programs_mutex_);
  std::string key = options;
  key += '\0';
  key += source;
  if (const auto it = programs_.find(key); it != programs_.end()) return it->second;
  const char* text = source.c_str();
  const std::size_t length = source.size();
  cl_int status = CL_SUCCESS;
  cl_program program = clCreateProgramWithSource(context_, 1, &text, &length, &status);
  check_cl(status, "clCreateProgramWithSource (" + name + ")");
  status = clBuildProgram(program, 1, &device_, options.c_str(), nullptr, nullptr);
  if (status != CL_SUCCESS) {
    const std::string log = build_log(program, device_);
    clReleaseProgram(program);
    check_cl(status, "clBuildProgram (" + name + ", options \"" + options + "\"): " + log);
  }
  programs_.emplace(std::move(key), program);
  return program;
}

}  // namespace bounce
