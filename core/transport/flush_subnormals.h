#pragma once
// Subnormal floats (below 1.2e-38) flushed to zero within a scope, on the
// calling thread and on OpenBLAS's worker threads.
//
// Why: the Cholesky and inverse of the transport's solve on the open Sponza
// meet so many subnormals that OpenBLAS's AVX-512 kernels ran five times
// slower (9-10.5 s a channel on one thread, 2.0 s with them flushed; each
// subnormal operand costs the CPU a microcode assist). They are 31 decades
// below the light the bake resolves, so flushing them changes nothing the
// bake stores beyond float32 rounding.
//
// How: FTZ and DAZ in the SSE control register of the calling thread.
// OpenBLAS's worker threads keep the mode of the thread that started them
// (new threads inherit it), so the scope stops them on entry and on exit
// (OpenBLAS restarts them at its next call, from the calling thread, in the
// mode then in force), while no other thread's product runs on them
// (blas_threads_mutex). A no-op on CPUs without SSE.
namespace bounce {

class FlushSubnormals {
 public:
  FlushSubnormals();
  ~FlushSubnormals();
  FlushSubnormals(const FlushSubnormals&) = delete;
  FlushSubnormals& operator=(const FlushSubnormals&) = delete;

 private:
  unsigned previous_ = 0;
};

}  // namespace bounce
