#include "runtime/frame_graph.h"

#include <algorithm>
#include <limits>
#include <string>

#include "base/error.h"

namespace bounce {

FrameGraph::ResourceId FrameGraph::add_transient(std::string name, std::size_t bytes) {
  resources_.push_back({std::move(name), bytes, true, nullptr});
  compiled_ = false;
  return resources_.size() - 1;
}

FrameGraph::ResourceId FrameGraph::add_imported(std::string name, void* data, std::size_t bytes) {
  resources_.push_back({std::move(name), bytes, false, data});
  compiled_ = false;
  return resources_.size() - 1;
}

void FrameGraph::add_pass(std::string name, std::vector<ResourceId> reads,
                          std::vector<ResourceId> writes, PassFunction run) {
  for (const auto* list : {&reads, &writes})
    for (ResourceId id : *list)
      if (id >= resources_.size())
        throw Error("frame graph", "pass " + name + " uses unknown resource " + std::to_string(id));
  passes_.push_back({std::move(name), std::move(reads), std::move(writes), std::move(run)});
  compiled_ = false;
}

void FrameGraph::compile(bool alias, std::size_t alignment) {
  const std::size_t none = passes_.size();
  std::vector<std::size_t> first(resources_.size(), none), last(resources_.size(), 0);
  std::vector<bool> written(resources_.size(), false);
  for (std::size_t p = 0; p < passes_.size(); ++p) {
    for (ResourceId id : passes_[p].reads) {
      if (resources_[id].transient && !written[id])
        throw Error("frame graph", "pass " + passes_[p].name + " reads " + resources_[id].name +
                                       " before any pass writes it");
      if (first[id] == none) first[id] = p;
      last[id] = p;
    }
    for (ResourceId id : passes_[p].writes) {
      written[id] = true;
      if (first[id] == none) first[id] = p;
      last[id] = p;
    }
  }
  lifetimes_.assign(resources_.size(), {});
  for (std::size_t r = 0; r < resources_.size(); ++r) {
    if (!resources_[r].transient) continue;
    if (first[r] == none)
      throw Error("frame graph", "transient " + resources_[r].name + " is never used");
    lifetimes_[r] = {first[r], last[r], resources_[r].bytes};
  }
  alignment_ = alignment;
  if (alias) {
    placement_ = place_transients(lifetimes_, alignment);
  } else {
    // Each transient its own range, in resource order.
    placement_ = {};
    for (const TransientLifetime& l : lifetimes_) {
      placement_.offsets.push_back(placement_.peak);
      placement_.peak += (l.bytes + alignment - 1) / alignment * alignment;
    }
  }
  arena_.assign((placement_.peak + sizeof(glm::vec4) - 1) / sizeof(glm::vec4), glm::vec4(0.0f));
  compiled_ = true;
}

void FrameGraph::execute() const {
  if (!compiled_) throw Error("frame graph", "execute() before compile()");
  const Context context(*this);
  if (!poison_) {
    for (const Pass& pass : passes_)
      if (pass.run) pass.run(context);
    return;
  }
  auto* floats = reinterpret_cast<float*>(arena_.data());
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::fill(floats, floats + arena_.size() * 4, nan);
  for (std::size_t p = 0; p < passes_.size(); ++p) {
    if (passes_[p].run) passes_[p].run(context);
    for (std::size_t r = 0; r < resources_.size(); ++r)
      if (resources_[r].transient && lifetimes_[r].last == p)
        std::fill_n(floats + placement_.offsets[r] / sizeof(float),
                    (resources_[r].bytes + sizeof(float) - 1) / sizeof(float), nan);
  }
}

void* FrameGraph::data(ResourceId id) const {
  if (id >= resources_.size()) throw Error("frame graph", "unknown resource " + std::to_string(id));
  if (!resources_[id].transient) return resources_[id].imported;
  if (!compiled_) throw Error("frame graph", "transient memory before compile()");
  return reinterpret_cast<std::byte*>(arena_.data()) + placement_.offsets[id];
}

std::size_t FrameGraph::unaliased_transient_bytes() const {
  return total_bytes(lifetimes_, alignment_);
}

std::size_t FrameGraph::max_live_transient_bytes() const {
  return max_live_bytes(lifetimes_, alignment_);
}

std::size_t FrameGraph::imported_bytes() const {
  std::size_t sum = 0;
  for (const Resource& r : resources_)
    if (!r.transient) sum += r.bytes;
  return sum;
}

FrameGraph dynamic_radiosity_memory_graph(std::size_t n, int channels, bool temporal) {
  FrameGraph g;
  const std::size_t per_channel = n * static_cast<std::size_t>(channels) * sizeof(float);
  const std::size_t colour = n * sizeof(glm::vec3);
  const auto matrix = g.add_imported("T", nullptr, 0);
  const auto f_c = g.add_transient("f_c", per_channel);
  const auto f_r = g.add_transient("f_r", per_channel);
  const auto a = g.add_transient("g''_c + f_c", per_channel);
  const auto b = g.add_transient("g''_r + f_r", per_channel);
  const auto e = g.add_transient("E", colour);
  const auto indirect = g.add_transient(temporal ? "B_new" : "B", colour);
  const auto output = g.add_imported("lit patches", nullptr, colour);
  g.add_pass("upload form factors", {}, {f_c, f_r}, {});
  g.add_pass("g''_c, g''_r", {matrix, f_c, f_r}, {a, b}, {});
  g.add_pass("matrix update", {a, b}, {matrix}, {});
  g.add_pass("direct light", {}, {e}, {});
  g.add_pass(temporal ? "temporal estimate" : "indirect product", {matrix, e}, {indirect}, {});
  if (temporal) {
    const auto history = g.add_imported("history", nullptr, colour);
    g.add_pass("temporal blend", {indirect, history}, {history}, {});
    g.add_pass("apply", {e, history}, {output}, {});
  } else {
    g.add_pass("apply", {e, indirect}, {output}, {});
  }
  return g;
}

}  // namespace bounce
