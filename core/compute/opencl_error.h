#pragma once
// The one exception type of every OpenCL failure, Bounce's own kernels and
// CLBlast's alike: the call that failed and its status, named when known.
#include <string>

#include "base/error.h"

namespace bounce {

class OpenClError : public Error {
 public:
  OpenClError(const std::string& call, int status);
  int status() const noexcept { return status_; }

 private:
  int status_;
};

}  // namespace bounce
