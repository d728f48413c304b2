#pragma once
// Systematic sampling of a discrete distribution: `draws` points spaced
// total / draws apart, the first at u * total / draws, fall on the intervals
// of a cumulative sum of non-negative masses. Item j is hit either
// floor(draws m_j / total) or one more times, and with u uniform in [0, 1)
// exactly draws m_j / total times on average, so weighting each hit by
// total / (draws m_j) gives an unbiased estimate of any sum over the items
// whose terms vanish where the mass does. Against independent draws the
// items whose mass exceeds total / draws are always hit (no variance from
// whether they are), and the others at most once each.
#include <cstdint>
#include <span>
#include <vector>

namespace bounce {

struct SystematicDraw {
  std::vector<std::uint32_t> items;  // the items hit, ascending, each once
  std::vector<double> scale;         // per hit item: hits * total / (draws * mass)
  double total = 0.0;                // the sum of the masses
};

// Throws bounce::Error when draws < 1, u is outside [0, 1) or a mass is
// negative or not finite. All masses 0: no items.
void systematic_draw(std::span<const double> mass, int draws, double u, SystematicDraw& out);

}  // namespace bounce
