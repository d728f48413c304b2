#pragma once
// The final gather's product spread over frames while its sources' light is
// not yet exact, as the shadow rays are (runtime/shadow_budget.h): with k
// frames, a frame whose sources still wait on shadow rays sums every k-th
// band of rows (a different band each frame) and the other rows keep the
// light they were last summed with. A frame whose sources are exact sums
// every row, so the gather is exact in the same frame as the shadows: k
// frames after a light stops. The product streams every entry of the
// gather and is bound by memory bandwidth (on Sponza 77 MiB and 9 ms a
// frame), so a k-th of its rows costs about a k-th of its time.
#include <cstddef>

namespace bounce {

// The rows a product sums: every row, or the bands of kRowBand rows whose
// index is `slice` modulo `slices`.
struct RowSlice {
  int slice = -1;  // -1: every row
  int slices = 1;
  bool all() const { return slice < 0; }
  bool sums_band(std::size_t band) const {
    return all() || static_cast<int>(band % static_cast<std::size_t>(slices)) == slice;
  }
};

// Rows per band: a few hundred kilobytes of entries, as the product's own
// bands on the threads.
inline constexpr std::size_t kRowBand = 1024;

class GatherRowBudget {
 public:
  // `frames`: k, at least 1 (1: every row every frame).
  explicit GatherRowBudget(int frames = 1);

  // This product's rows: every row when `sources_exact` (or k is 1, or
  // `restart`: the rows kept hold nothing yet), else the next k-th.
  RowSlice next(bool sources_exact, bool restart);
  // No row lags behind its sources: the last product summed every row (or
  // there was none yet). Whether the sources are exact is the shadow
  // budgets' to say.
  bool settled() const { return settled_; }
  int frames() const { return frames_; }
  // What the last next() returned.
  RowSlice last() const { return last_; }

 private:
  int frames_;
  int cursor_ = 0;
  bool settled_ = true;
  RowSlice last_;
};

}  // namespace bounce
