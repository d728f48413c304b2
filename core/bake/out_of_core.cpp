#include "bake/out_of_core.h"

#include "transport/text_format.h"

namespace bounce {

namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

}  // namespace

std::size_t dense_footprint_bytes(std::size_t n) { return 6 * n * n * sizeof(float); }

OutOfCoreDecision decide_out_of_core(const BakeSettings& settings, std::size_t patches,
                                     std::size_t physical_memory) {
  OutOfCoreDecision d;
  d.dense_footprint_bytes = dense_footprint_bytes(patches);
  d.physical_memory_bytes = physical_memory;
  d.dir = settings.out_of_core_dir.empty() ? default_out_of_core_dir()
                                           : std::filesystem::path(settings.out_of_core_dir);
  const double footprint = static_cast<double>(d.dense_footprint_bytes) / kGiB;
  const double memory = static_cast<double>(physical_memory) / kGiB;
  switch (settings.out_of_core) {
    case OutOfCore::On:
      d.on = true;
      d.why = "requested ('out_of_core' on)";
      break;
    case OutOfCore::Off:
      d.why = "requested ('out_of_core' off)";
      break;
    case OutOfCore::Auto:
      d.on = physical_memory > 0 && d.dense_footprint_bytes > physical_memory / 2;
      d.why = physical_memory == 0
                  ? "physical memory unknown: in memory"
                  : text_format(
                        "dense matrices of the transport stage (6 x %zu^2 floats) %.2f "
                        "GiB %s half the physical memory (%.1f GiB)",
                        patches, footprint, d.on ? "exceed" : "fit in", memory);
      break;
  }
  return d;
}

std::optional<OutOfCorePolicy> policy_of(const OutOfCoreDecision& decision) {
  if (!decision.on) return std::nullopt;
  return OutOfCorePolicy{decision.dir};
}

}  // namespace bounce
