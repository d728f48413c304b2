#pragma once
// The process-wide OpenCL device for Bounce's own kernels (kernels/*.cl): one
// context and one in-order queue on the first GPU, else the first device of
// any kind (PoCL's CPU device on the build machines), and a cache of built
// programs keyed by source and build options, so a kernel is compiled once
// per process (PoCL takes a noticeable fraction of a second per build).
//
// Every OpenCL failure becomes an OpenClError (compute/opencl_error.h, the
// same type CLBlast's failures use) through check_cl(), naming the call and
// its status.
//
// CLBlast (transport/clblast_gemm.cpp) runs on this context and queue too.
#ifndef CL_TARGET_OPENCL_VERSION
// OpenCL 1.2 is what every driver offers (PoCL, Mesa, the GPU vendors').
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>

#include <map>
#include <mutex>
#include <string>

#include "compute/opencl_error.h"

namespace bounce {

// Throws OpenClError(call, status) unless status is CL_SUCCESS.
void check_cl(cl_int status, const std::string& call);

class OpenClContext {
 public:
  // Opens the device on first use. Throws bounce::Error (an OpenClError the
  // first time) when OpenCL has no platform or device; the failure is
  // remembered, so later calls throw at once without probing the driver again.
  static OpenClContext& shared();

  OpenClContext(const OpenClContext&) = delete;
  OpenClContext& operator=(const OpenClContext&) = delete;

  cl_context context() const { return context_; }
  cl_command_queue queue() const { return queue_; }
  cl_device_id device() const { return device_; }
  const std::string& device_name() const { return device_name_; }

  // The built program for `source` with build `options` (cached). `name`
  // only labels errors: a failed build throws OpenClError with the build log.
  cl_program program(const std::string& name, const std::string& source,
                     const std::string& options);

  // Held by whoever enqueues work on queue(): the queue is shared, and a
  // sequence of uploads, launches and reads must not interleave with
  // another thread's.
  std::mutex& queue_mutex() { return queue_mutex_; }

 private:
  OpenClContext();
  // Never destroyed (shared() leaks it on purpose): releasing OpenCL objects
  // from a static destructor races with the driver's own teardown at exit
  // (a known PoCL crash).
  ~OpenClContext() = default;

  cl_device_id device_ = nullptr;
  cl_context context_ = nullptr;
  cl_command_queue queue_ = nullptr;
  std::string device_name_;
  std::mutex programs_mutex_;
  std::map<std::string, cl_program> programs_;  // key: options + '\0' + source
  std::mutex queue_mutex_;
};

}  // namespace bounce
