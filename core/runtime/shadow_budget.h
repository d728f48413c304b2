#pragma once
// Shadow rays from many points (the patches' samples, the final gather's
// near sources) to the point, spot and directional lights, spread over
// frames while a light moves, as Enlighten spreads its updates over a budget
// per frame. The points come in batches (runs of consecutive points); each
// frame after a light moved traces every k-th batch (a different one each
// frame), and the others keep the visibility they were last traced with.
// Their unshadowed light is still computed every frame: only whether
// something is in the way lags. k frames after a light stops, every batch has been traced at its
// last place, so the light is exactly what tracing every ray gives; a light
// that does not move traces nothing. k = 1 traces every ray of every light
// that moved, every frame.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace bounce {

class ShadowBudget {
 public:
  // `frames`: k, at least 1.
  explicit ShadowBudget(int frames = 1);

  // Starts a frame: `batches` batches of points whose first position is at
  // `points` (its address names the set), lit by `lights`. Everything is
  // traced when the points or the number or kinds of lights changed.
  void begin_frame(const void* points, std::size_t batches, const std::vector<Light>& lights);
  // Whether batch `b`'s rays to light `l` are traced this frame.
  bool traced(std::size_t l, std::size_t b) const {
    const int slice = slice_[l];
    return slice == kAll || (slice >= 0 && static_cast<int>(b % frames_) == slice);
  }
  // Point i's visibility of light l (1: nothing in the way), as last traced:
  // written when traced, read otherwise. Sized for `points` points by
  // visibility_of().
  std::vector<std::uint8_t>& visibility_of(std::size_t l, std::size_t points);

  int frames() const { return static_cast<int>(frames_); }
  // No light has batches left to trace since it last moved: the kept
  // visibility is exact.
  bool settled() const;
  // Batches traced in the last frame, over all lights.
  std::size_t traced_batches() const { return traced_batches_; }

 private:
  static constexpr int kAll = -1, kNone = -2;
  std::size_t frames_;
  const void* points_ = nullptr;
  std::size_t batches_ = 0;
  std::vector<Light> lights_;
  // Per light: this frame's slice (kAll, kNone or a batch index mod k), the
  // slices still to trace since it last moved, and the next slice.
  std::vector<int> slice_, pending_, cursor_;
  std::vector<std::vector<std::uint8_t>> visibility_;
  std::size_t traced_batches_ = 0;
};

}  // namespace bounce
