#include "progress_callback.h"

#include <string>
#include <utility>

namespace py = pybind11;

namespace bounce::python {

ProgressCallback::ProgressCallback(py::object callable)
    : callable_(std::move(callable)),
      progress_(callable_.is_none()
                    ? Progress::Callback{}
                    : Progress::Callback([this](const std::string& stage, double fraction) {
                        return report(stage, fraction);
                      })) {}

ProgressCallback::~ProgressCallback() {
  // Dropping the callable needs the GIL; the owner may hold it or not.
  py::gil_scoped_acquire gil;
  callable_ = py::object();
}

bool ProgressCallback::report(const std::string& stage, double fraction) {
  py::gil_scoped_acquire gil;
  try {
    const py::object answer = callable_(stage, fraction);
    // None (a callable that returns nothing) goes on; only a false answer stops.
    return answer.is_none() || answer.cast<bool>();
  } catch (...) {
    std::lock_guard lock(raised_mutex_);
    if (!raised_) raised_ = std::current_exception();
    return false;
  }
}

void ProgressCallback::rethrow_if_raised() {
  std::exception_ptr raised;
  {
    std::lock_guard lock(raised_mutex_);
    raised = std::exchange(raised_, nullptr);
  }
  if (raised) std::rethrow_exception(raised);
}

}  // namespace bounce::python
