#include "dynamic/systematic_draw.h"

#include <cmath>
#include <limits>
#include <string>

#include "base/error.h"

namespace bounce {

void systematic_draw(std::span<const double> mass, int draws, double u, SystematicDraw& out) {
  if (draws < 1) throw Error("systematic draw", "needs at least one draw");
  if (!(u >= 0.0 && u < 1.0)) throw Error("systematic draw", "offset outside [0, 1)");
  if (mass.size() > std::numeric_limits<std::uint32_t>::max())
    throw Error("systematic draw", "too many items for 32-bit indices");
  out.items.clear();
  out.scale.clear();
  double total = 0.0;
  for (double m : mass) {
    if (!(m >= 0.0 && std::isfinite(m)))
      throw Error("systematic draw", "mass " + std::to_string(m) + " is negative or not finite");
    total += m;
  }
  out.total = total;
  if (!(total > 0.0)) return;
  const double step = total / draws;
  int next = 0;  // the next point, at (next + u) * step
  double end = 0.0;
  std::size_t last_hit = mass.size();
  for (std::size_t j = 0; j < mass.size() && next < draws; ++j) {
    if (mass[j] <= 0.0) continue;
    end += mass[j];
    int hits = 0;
    while (next < draws && (next + u) * step < end) {
      ++hits;
      ++next;
    }
    if (hits == 0) continue;
    out.items.push_back(static_cast<std::uint32_t>(j));
    out.scale.push_back(hits * step / mass[j]);
    last_hit = j;
  }
  // Rounding in the running sum can leave the last points just past its
  // end; they belong to the last item with mass (at most a few ulps of the
  // total decide this, far below the estimate's noise).
  if (next < draws) {
    std::size_t j = mass.size();
    while (j > 0 && !(mass[j - 1] > 0.0)) --j;
    const std::size_t item = j - 1;
    const int hits = draws - next;
    if (last_hit == item) {
      out.scale.back() += hits * step / mass[item];
    } else {
      out.items.push_back(static_cast<std::uint32_t>(item));
      out.scale.push_back(hits * step / mass[item]);
    }
  }
}

}  // namespace bounce
