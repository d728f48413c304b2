#pragma once
// T b through the matrix of a bake in memory (not yet written to a folder),
// the way `bounce solve` multiplies it on a CPU: the dense sgemv, or the
// compressed C++ product (runtime/transport_multiplier.h, kAutoCpu). Shared
// by `bounce bake --reference`, the report sweep and the studio's report.
#include <memory>

#include "bake/bake.h"
#include "runtime/patch_lighting.h"

namespace bounce {

// The returned function owns what it multiplies with, except a dense bake's
// matrices, which stay in `transport`; `keep_alive` is no longer needed and
// is left untouched.
IndirectMultiply baked_multiply(const TransportResult& transport, const MatrixStorage& storage,
                                std::shared_ptr<void>& keep_alive);

}  // namespace bounce
