#pragma once
// OpenCL C sources of Bounce's kernels (kernels/*.cl). They are
// embedded in the library at build time (core/CMakeLists.txt turns each file
// into a raw string), so a binary runs from anywhere; for kernel work without
// a rebuild, BOUNCE_KERNEL_DIR=<folder> makes <folder>/<name>.cl override the
// embedded copy when that file exists.
#include <string>

namespace bounce {

// The source of kernels/<name>.cl. Throws bounce::Error when no kernel has
// that name, or when the override file exists but cannot be read.
std::string kernel_source(const std::string& name);

}  // namespace bounce
