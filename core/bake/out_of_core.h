#pragma once
// Whether a bake keeps its finished dense matrices (F once checked, each
// channel's T once solved) in memory-mapped temporary files
// (base/mapped_buffer.h, spill_to_file), decided once the patch count N is
// known. Matrices being computed stay on the heap.
//
// In memory, the transport stage holds at most F, one channel's M (becoming
// its T) and two n x n work buffers (a float64 LU factorisation; the doubling
// series' P and product) besides the channels already finished: for three
// channels (1 + 3 + 2) n^2 floats. Auto maps when that exceeds half the
// machine's physical memory, which leaves room for everything else and for
// the other processes on the machine.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "base/mapped_buffer.h"
#include "settings/bake_settings.h"

namespace bounce {

struct OutOfCoreDecision {
  bool on = false;
  std::filesystem::path dir;              // where the files go (when on)
  std::size_t dense_footprint_bytes = 0;  // (1 + 3 + 2) n^2 floats
  std::size_t physical_memory_bytes = 0;
  std::string why;  // for the manifest
};

// Dense footprint of the transport stage for n patches, in bytes.
std::size_t dense_footprint_bytes(std::size_t n);

OutOfCoreDecision decide_out_of_core(const BakeSettings& settings, std::size_t patches,
                                     std::size_t physical_memory = physical_memory_bytes());

// The mapping policy for a decision (empty when off).
std::optional<OutOfCorePolicy> policy_of(const OutOfCoreDecision& decision);

}  // namespace bounce
