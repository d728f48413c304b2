#include "transport/flush_subnormals.h"

#include <dlfcn.h>

#include <mutex>

#include "transport/blas_kernels.h"

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace bounce {

namespace {

#if defined(__SSE2__)
constexpr unsigned kFlushToZero = 0x8000u;     // FTZ: subnormal results become 0
constexpr unsigned kDenormalsAreZero = 0x40u;  // DAZ: subnormal operands read as 0
#endif

// OpenBLAS's worker threads stopped; its next call starts them again from
// the calling thread. Nothing when this BLAS has no such pool.
void restart_blas_threads() {
  const std::unique_lock lock(blas_threads_mutex());
  using Shutdown = int (*)();
  if (const auto shutdown =
          reinterpret_cast<Shutdown>(dlsym(RTLD_DEFAULT, "blas_thread_shutdown_")))
    shutdown();
}

}  // namespace

FlushSubnormals::FlushSubnormals() {
#if defined(__SSE2__)
  previous_ = _mm_getcsr();
  _mm_setcsr(previous_ | kFlushToZero | kDenormalsAreZero);
  restart_blas_threads();
#endif
}

FlushSubnormals::~FlushSubnormals() {
#if defined(__SSE2__)
  _mm_setcsr(previous_);
  restart_blas_threads();
#endif
}

}  // namespace bounce
