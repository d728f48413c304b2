#pragma once
// Public: the BLAS kernels the dense algebra runs on.
//
//   const bounce::BlasKernels& k = bounce::choose_blas_kernels();  // at start-up
//   std::printf("OpenBLAS kernels: %s (%s)\n", k.used.c_str(), k.why.c_str());
//
// The library calls it itself before its first dense product (the switch
// waits for any dense product other threads run); a program
// that may run BLAS on several threads calls it once at start-up, before
// any of them does.
#include "transport/blas_kernels.h"
