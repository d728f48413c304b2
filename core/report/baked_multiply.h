#pragma once
// T b through a bake's stored matrix, the way `bounce solve` multiplies it on
// a CPU: the dense sgemv, or the compressed C++ product. Shared by `bounce
// bake --reference`, the report sweep and the studio's report.
#include <memory>

#include "bake/bake.h"
#include "runtime/patch_lighting.h"

namespace bounce {

// `keep_alive` holds what the returned function uses.
IndirectMultiply baked_multiply(const TransportResult& transport, const MatrixStorage& storage,
                                std::shared_ptr<void>& keep_alive);

}  // namespace bounce
