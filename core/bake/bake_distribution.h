#pragma once
// How Baker::run shares its stages with other processes (core/distributed:
// MPI ranks). Every process runs the same pipeline on the same scene up to the
// form factors; each computes only its share of the form-factor rows, and
// merge_form_factors gathers the full matrix on the root. The root then runs
// the rest of the bake alone, handing the dense algebra of the transport
// stage to transport_executor(); the other processes serve that executor
// (serve_transport) and return without a result. Without a distribution
// (nullptr) Baker::run is the single-process bake, unchanged.
#include <cstdint>
#include <memory>

#include "base/progress.h"
#include "formfactor/form_factors.h"
#include "patches/patch_set.h"
#include "transport/transport_executor.h"

namespace bounce {

class BakeDistribution {
 public:
  virtual ~BakeDistribution() = default;
  virtual bool is_root() const = 0;
  // The form-factor rows this process computes (FormFactorSettings).
  virtual std::size_t row_offset() const = 0;
  virtual std::size_t row_stride() const = 0;
  // Collective; throws on every process when the processes computed
  // different patches (each computes them for itself, and rows computed for
  // different patches would not fit together).
  virtual void check_same_patches(const PatchSet& patches) = 0;
  // Collective: every process's rows into the full matrix, on the root (the
  // other processes' matrices are left as they were).
  virtual void merge_form_factors(FormFactorMatrix& f) = 0;
  // Root: the executor the transport stage uses; its destruction releases
  // the other processes from serve_transport.
  virtual std::unique_ptr<TransportExecutor> transport_executor() = 0;
  // Not the root: takes part in the root's products and solves until the
  // root's executor is destroyed.
  virtual void serve_transport() = 0;
};

}  // namespace bounce
