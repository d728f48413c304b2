#include "runtime/gather_row_budget.h"

#include "base/error.h"

namespace bounce {

GatherRowBudget::GatherRowBudget(int frames) : frames_(frames) {
  if (frames < 1) throw Error("final gather", "the gather's frames must be at least 1");
}

RowSlice GatherRowBudget::next(bool sources_exact, bool restart) {
  settled_ = sources_exact || restart || frames_ == 1;
  if (settled_) return last_ = {};
  last_ = {cursor_, frames_};
  cursor_ = (cursor_ + 1) % frames_;
  return last_;
}

}  // namespace bounce
