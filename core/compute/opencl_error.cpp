#include "compute/opencl_error.h"

#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>

namespace bounce {

namespace {

const char* status_name(int status) {
  switch (status) {
    case CL_DEVICE_NOT_FOUND:
      return "CL_DEVICE_NOT_FOUND";
    case CL_DEVICE_NOT_AVAILABLE:
      return "CL_DEVICE_NOT_AVAILABLE";
    case CL_COMPILER_NOT_AVAILABLE:
      return "CL_COMPILER_NOT_AVAILABLE";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE:
      return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_OUT_OF_RESOURCES:
      return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY:
      return "CL_OUT_OF_HOST_MEMORY";
    case CL_BUILD_PROGRAM_FAILURE:
      return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_VALUE:
      return "CL_INVALID_VALUE";
    case CL_INVALID_PLATFORM:
      return "CL_INVALID_PLATFORM";
    case CL_INVALID_DEVICE:
      return "CL_INVALID_DEVICE";
    case CL_INVALID_CONTEXT:
      return "CL_INVALID_CONTEXT";
    case CL_INVALID_COMMAND_QUEUE:
      return "CL_INVALID_COMMAND_QUEUE";
    case CL_INVALID_MEM_OBJECT:
      return "CL_INVALID_MEM_OBJECT";
    case CL_INVALID_BUFFER_SIZE:
      return "CL_INVALID_BUFFER_SIZE";
    case -1001:
      return "CL_PLATFORM_NOT_FOUND_KHR (no OpenCL driver installed)";
    case -2041:
      return "CLBlast kDatabaseError (no tuning entry for this device)";
    case -2046:
      return "CLBlast kInvalidLocalMemUsage";
    case -2040:
      return "CLBlast kUnknownError";
    case -2039:
      return "CLBlast kUnexpectedError";
    default:
      return nullptr;
  }
}

std::string describe(const std::string& call, int status) {
  const char* name = status_name(status);
  return call + " failed with status " + std::to_string(status) +
         (name ? std::string(" (") + name + ")" : std::string());
}

}  // namespace

OpenClError::OpenClError(const std::string& call, int status)
    : Error("OpenCL", describe(call, status)), status_(status) {}

}  // namespace bounce
