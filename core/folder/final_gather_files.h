#pragma once
// The final gather of a bake's lit-mesh vertices (runtime/final_gather.h) as
// files of the bake folder (docs/bake-format.md):
//   gather_first.npy   <u4 [vertices + 1]   row starts
//   gather_source.npy  <u4 [entries]        patch index, or patches + cluster,
//                                           or patches + clusters + sample,
//                                           or patches + clusters + samples +
//                                           near source
//   gather_weight.npy  <f4 [entries]        point-to-source form factor
//   gather_cluster.npy <u4 [patches]        each patch's cluster
//   gather_share.npy   <f4 [patches]        its share of the cluster's light
//   gather_seen_first.npy <u4 [patches + 1], gather_seen_sample.npy <u4 [k],
//   gather_seen_weight.npy <f4 [k]          each patch's samples weighed by
//                                           the rays that landed on them
//                                           (absent: area weights)
//   gather_near_position.npy, gather_near_normal.npy, gather_near_albedo.npy
//                      <f4 [near, 3]        the near sources (absent: none)
//   gather_near_patch.npy <u4 [near]        the patch whose T b each carries
// The vertices are those build_transfer_mesh makes from the scene and the
// bake's grid with default settings, in its order; a reader rebuilds that
// mesh and checks the count.
#include <filesystem>
#include <optional>
#include <string>

#include "runtime/final_gather.h"

namespace bounce {

void write_final_gather(const std::filesystem::path& dir, const FinalGather& gather);

// nullopt when the folder has no gather (a bake made without one); throws
// bounce::Error naming the file when the files are there but inconsistent
// with each other, with `patches` or with `samples` (the bake's sample count,
// which sample sources index).
std::optional<FinalGather> read_final_gather(const std::filesystem::path& dir, std::size_t patches,
                                             std::size_t samples);

// The same for another gather stored beside it, each file named as the
// vertices' with "gather_" replaced by `prefix` (the light probes':
// bake_file::kProbeGatherPrefix).
void write_final_gather(const std::filesystem::path& dir, const FinalGather& gather,
                        const char* prefix);
// A vertices' gather file name (bake_file::kGather...) under `prefix`.
std::string gather_file_name(const char* prefix, const char* vertex_name);
std::optional<FinalGather> read_final_gather(const std::filesystem::path& dir, std::size_t patches,
                                             std::size_t samples, const char* prefix);

}  // namespace bounce
