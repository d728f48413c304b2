#pragma once
// A small frame graph (after O'Donnell's FrameGraph): passes run
// in the order they are added, each declaring the resources it reads and
// writes. Resources are either imported (persistent: owned by the caller,
// e.g. the matrix, the temporal history, the output) or transient (live
// only within the frame, memory owned by the graph). compile() derives each
// transient's lifetime (first to last pass that touches it) and places all
// transients in one arena, with aliasing (runtime/transient_allocator.h) or
// without (each its own range), so the two can be measured and run on the
// same code path. execute() runs the passes; a pass reaches its resources'
// memory through the context.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "runtime/transient_allocator.h"

namespace bounce {

class FrameGraph {
 public:
  using ResourceId = std::size_t;

  class Context {
   public:
    explicit Context(const FrameGraph& graph) : graph_(graph) {}
    template <class T>
    T* get(ResourceId id) const {
      return static_cast<T*>(graph_.data(id));
    }

   private:
    const FrameGraph& graph_;
  };
  using PassFunction = std::function<void(const Context&)>;

  ResourceId add_transient(std::string name, std::size_t bytes);
  ResourceId add_imported(std::string name, void* data, std::size_t bytes);
  // Throws bounce::Error on an unknown resource id.
  void add_pass(std::string name, std::vector<ResourceId> reads, std::vector<ResourceId> writes,
                PassFunction run);

  // Lifetimes and placement. Throws bounce::Error naming the resource when a
  // transient is read before any pass writes it or is never used. Allocates
  // the arena.
  void compile(bool alias, std::size_t alignment = 256);
  // Runs every pass in order (compile() first).
  void execute() const;
  // Checking mode (tests, debugging): execute() first fills the whole arena
  // with NaN and, after each pass, the range of every transient whose
  // lifetime ended with that pass. A pass that read memory no live resource
  // owns, or an aliasing that let a dead buffer's range cover a live one,
  // then shows as NaN in the outputs. Off by default (it costs a write of
  // the arena per frame).
  void set_poison_dead_transients(bool on) { poison_ = on; }

  // After compile(): the arena size, and what the transients would take
  // without aliasing; the imported resources' bytes (not in the arena).
  std::size_t transient_bytes() const { return placement_.peak; }
  std::size_t unaliased_transient_bytes() const;
  std::size_t max_live_transient_bytes() const;
  std::size_t imported_bytes() const;
  // The memory actually allocated for the arena (transient_bytes() rounded
  // up to the storage's 16-byte units).
  std::size_t arena_bytes() const { return arena_.size() * sizeof(glm::vec4); }

  struct Resource {
    std::string name;
    std::size_t bytes = 0;
    bool transient = true;
    void* imported = nullptr;
  };
  struct Pass {
    std::string name;
    std::vector<ResourceId> reads, writes;
    PassFunction run;
  };
  const std::vector<Resource>& resources() const { return resources_; }
  const std::vector<Pass>& passes() const { return passes_; }
  // After compile(): lifetime and offset of every transient, in resource order
  // (imported ones: zero size).
  const std::vector<TransientLifetime>& lifetimes() const { return lifetimes_; }
  const std::vector<std::size_t>& offsets() const { return placement_.offsets; }

 private:
  void* data(ResourceId id) const;
  std::vector<Resource> resources_;
  std::vector<Pass> passes_;
  std::vector<TransientLifetime> lifetimes_;
  TransientPlacement placement_;
  std::size_t alignment_ = 256;
  bool compiled_ = false;
  bool poison_ = false;
  // 16-byte aligned storage; offsets are multiples of the alignment.
  mutable std::vector<glm::vec4> arena_;
};

// The per-frame graph of dynamic radiosity for n patches and `channels`
// stored channels, resources as the published dynamic method lays them out (sizes only, no work):
// local-matrix update (f_c, f_r, a = g''_c + f_c, b = g''_r + f_r: one float
// per patch and channel each), direct light E and indirect B (a vec3 per
// patch), the temporal history (imported) when `temporal`, applied to the
// output (imported). For the memory table.
FrameGraph dynamic_radiosity_memory_graph(std::size_t n, int channels, bool temporal);

}  // namespace bounce
