// Which wide instruction sets this CPU runs (block_loops.h declares them):
// the compressed matrix's block loops and the final gather's row loops offer
// a wide loop only where it runs, then time the ones offered. Apart from the
// loops themselves so that a reader that packs rows (the fuzzed bake reader)
// links these checks without the block loops' tables.
#include "runtime/block_loops.h"

namespace bounce::block_loops {

#ifdef BOUNCE_AVX2_BLOCK_LOOP
bool cpu_has_avx2() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }
bool cpu_has_avx512() { return __builtin_cpu_supports("avx512f") && cpu_has_avx2(); }
bool cpu_has_avx512_bf16() {
  return cpu_has_avx512() && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512vbmi") &&
         __builtin_cpu_supports("avx512bf16");
}

#else
bool cpu_has_avx2() { return false; }
bool cpu_has_avx512() { return false; }
bool cpu_has_avx512_bf16() { return false; }
#endif

}  // namespace bounce::block_loops
