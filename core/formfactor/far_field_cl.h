#pragma once
// The far-field sums of formfactor/far_field.h on the OpenCL device
// (compute/opencl_context.h: the first GPU, else PoCL's CPU device here),
// kernel kernels/far_field.cl. Same result as far_field_sums, to float
// rounding. The C++ path stays the one the bake uses; this one exists to be
// measured against it (docs/benchmarks.md, "Far-field form factors").
#include <string>
#include <vector>

#include "formfactor/far_field.h"

namespace bounce {

// As far_field_sums: uploads the points, runs one kernel over all pairs and
// reads the n x n sums back. Throws bounce::Error when OpenCL has no device
// (OpenClError on any OpenCL failure, including running out of device
// memory) or the points are inconsistent. Thread-safe (serialised on the
// shared queue).
std::vector<float> far_field_sums_cl(const FarPoints& points);

// The name of the device far_field_sums_cl runs on (opens it).
std::string far_field_device_name();

}  // namespace bounce
