#pragma once
// A Python callable as the core's Progress: it is called as
// callable(stage, fraction), under the GIL, from whichever thread reports;
// returning False asks the work to stop (the core then throws Cancelled).
// An exception the callable raises also stops the work, and is raised again
// by rethrow_if_raised() in place of the cancellation.
#include <exception>
#include <mutex>

#include <pybind11/pybind11.h>

#include "bounce/bake.h"

namespace bounce::python {

class ProgressCallback {
 public:
  // `callable` may be None: no reports, no stop.
  explicit ProgressCallback(pybind11::object callable);
  ~ProgressCallback();
  ProgressCallback(const ProgressCallback&) = delete;
  ProgressCallback& operator=(const ProgressCallback&) = delete;

  Progress& progress() { return progress_; }
  // Raises the callable's exception, if it raised one. Call with the GIL.
  void rethrow_if_raised();

 private:
  bool report(const std::string& stage, double fraction);

  pybind11::object callable_;
  std::mutex raised_mutex_;
  std::exception_ptr raised_;
  Progress progress_;
};

}  // namespace bounce::python
