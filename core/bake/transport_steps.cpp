// The last two stages of a bake: the multi-bounce transport matrices, and
// how they are stored (dense or compressed, with their errors).
#include "bake/bake_steps.h"
#include "bake/vertex_light_error.h"

namespace bounce {

namespace {

void transport_step(BakeRun& run) {
  BakeResult& r = run.result;
  std::vector<glm::vec3> albedo;
  albedo.reserve(r.patches.size());
  for (const Patch& p : r.patches.patches) albedo.push_back(p.albedo);
  {
    const OutOfCoreScope scope(run.out_of_core);  // where compute_transport puts each T
    r.transport = compute_transport(r.form_factors, albedo, r.settings.transport, &run.progress,
                                    run.diagnostics, run.executor.get());
  }
  run.executor.reset();  // the other processes are done
  // F is not read again until the bake is written: out of core, its pages
  // go back to their file (no-op for a heap matrix).
  release_residency(r.form_factors.values);
  r.probe.channel_of_rgb = channel_of_rgb(r.transport);
}

void compress_step(BakeRun& run) {
  BakeResult& r = run.result;
  r.storage = store_transport(r.transport, r.probe, r.settings, &run.progress, run.diagnostics,
                              run.compressor.get());
  if (r.storage.compressed && r.vertex_gather.points() > 0)
    r.storage.vertex_indirect =
        vertex_light_error(r.vertex_gather, r.samples, r.patches, stored_channels(r.transport),
                           *r.storage.compressed, r.probe);
  for (const ChannelTransport& c : r.transport.channels) release_residency(c.t);
}

constexpr BakeStep kTransportSteps[] = {
    {"transport", nullptr, transport_step},
};

constexpr BakeStep kCompressionSteps[] = {
    {"compress", nullptr, compress_step},
};

}  // namespace

std::span<const BakeStep> transport_steps() { return kTransportSteps; }
std::span<const BakeStep> compression_steps() { return kCompressionSteps; }

}  // namespace bounce
