#include "compress/ordering_tour.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace bounce {
namespace {

double distance(const float* points, std::size_t dims, std::uint32_t a, std::uint32_t b) {
  return std::sqrt(static_cast<double>(
      squared_distance(points + std::size_t{a} * dims, points + std::size_t{b} * dims, dims)));
}

// A closed tour as an array plus the position of each node.
class Tour {
 public:
  explicit Tour(Permutation& order) : order_(order), n_(order.size()), pos_(order.size()) {
    for (std::size_t i = 0; i < n_; ++i) pos_[order_[i]] = static_cast<std::uint32_t>(i);
  }
  std::uint32_t next(std::uint32_t v) const { return order_[(pos_[v] + 1) % n_]; }
  std::uint32_t prev(std::uint32_t v) const { return order_[(pos_[v] + n_ - 1) % n_]; }
  std::uint32_t step(std::uint32_t v, bool forward) const { return forward ? next(v) : prev(v); }

  // Replaces edges (a, b) and (c, d) by (a, c) and (b, d). Requires b and d to
  // lie on the same side of a and c: b = next(a), d = next(c) or
  // b = prev(a), d = prev(c).
  void two_opt_move(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    if (b == next(a))
      reverse(b, c);  // a [b ... c] d  ->  a c ... b d
    else
      reverse(a, d);  // b [a ... d] c  ->  b d ... a c
  }

 private:
  // Reverses the forward path from node `from` to node `to`. Reversing the
  // complementary path gives the same cycle (read the other way round), so
  // the shorter of the two is reversed.
  void reverse(std::uint32_t from, std::uint32_t to) {
    std::size_t i = pos_[from], j = pos_[to];
    std::size_t len = (j + n_ - i) % n_ + 1;
    if (2 * len > n_) {
      const std::size_t ni = (j + 1) % n_, nj = (i + n_ - 1) % n_;
      i = ni;
      j = nj;
      len = n_ - len;
    }
    for (std::size_t s = 0; s < len / 2; ++s) {
      const std::size_t pi = (i + s) % n_, pj = (j + n_ - s) % n_;
      std::swap(order_[pi], order_[pj]);
      pos_[order_[pi]] = static_cast<std::uint32_t>(pi);
      pos_[order_[pj]] = static_cast<std::uint32_t>(pj);
    }
  }

  Permutation& order_;
  std::size_t n_;
  std::vector<std::uint32_t> pos_;
};

}  // namespace

double tour_length(const float* points, std::size_t dims, const Permutation& order, bool cycle) {
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < order.size(); ++i)
    length += distance(points, dims, order[i], order[i + 1]);
  if (cycle && order.size() > 2) length += distance(points, dims, order.back(), order.front());
  return length;
}

Permutation greedy_sketch_tour(const float* points, std::size_t n, std::size_t dims,
                               const NeighbourLists& nn, std::uint32_t start) {
  Permutation path;
  if (n == 0) return path;
  path.reserve(n);
  std::vector<char> visited(n, 0);
  // Unvisited points, compact (swap-remove), for the fallback scans.
  std::vector<std::uint32_t> left(n), slot(n);
  for (std::size_t i = 0; i < n; ++i) left[i] = slot[i] = static_cast<std::uint32_t>(i);
  auto visit = [&](std::uint32_t v) {
    visited[v] = 1;
    const std::uint32_t s = slot[v];
    left[s] = left.back();
    slot[left[s]] = s;
    left.pop_back();
    path.push_back(v);
  };
  visit(start);
  while (!left.empty()) {
    const std::uint32_t cur = path.back();
    std::uint32_t best = std::numeric_limits<std::uint32_t>::max();
    // Candidate lists are sorted nearest first: the first unvisited entry is
    // the nearest unvisited point.
    for (std::size_t t = 0; t < nn.k; ++t)
      if (!visited[nn.of(cur)[t]]) {
        best = nn.of(cur)[t];
        break;
      }
    if (best == std::numeric_limits<std::uint32_t>::max()) {
      // Serial on purpose: one scan is O(n dims), a fraction of a millisecond
      // at n = 16384, less than an OpenMP fork/join costs on a busy machine.
      const float* p = points + std::size_t{cur} * dims;
      float best_d = std::numeric_limits<float>::infinity();
      for (const std::uint32_t v : left) {
        const float d = squared_distance(p, points + std::size_t{v} * dims, dims);
        if (d < best_d || (d == best_d && v < best)) {
          best_d = d;
          best = v;
        }
      }
    }
    visit(best);
  }
  return path;
}

TourImprovement improve_tour(const float* points, std::size_t n, std::size_t dims,
                             const NeighbourLists& nn, Permutation& order, std::size_t max_moves) {
  TourImprovement result;
  // Below 8 points a segment move and its neighbourhood overlap the whole
  // tour; there is nothing worth searching.
  if (n < 8 || nn.k == 0) return result;
  Tour tour(order);
  auto d = [&](std::uint32_t a, std::uint32_t b) { return distance(points, dims, a, b); };
  // Moves must gain more than this: rounding can never make the search cycle.
  const double eps =
      1e-9 * std::max(1e-30, tour_length(points, dims, order, true) / static_cast<double>(n));

  // Don't-look bits as a FIFO queue of points whose neighbourhood changed.
  std::vector<std::uint32_t> queue(order.begin(), order.end());
  std::vector<char> queued(n, 1);
  std::size_t head = 0;
  auto push = [&](std::uint32_t v) {
    if (!queued[v]) {
      queued[v] = 1;
      queue.push_back(v);
    }
  };

  auto try_two_opt = [&](std::uint32_t a) {
    for (const bool forward : {true, false}) {
      const std::uint32_t b = tour.step(a, forward);
      const double dab = d(a, b);
      for (std::size_t t = 0; t < nn.k; ++t) {
        const std::uint32_t c = nn.of(a)[t];
        const double dac = d(a, c);
        if (dac >= dab - eps) break;  // sorted lists: no later c can gain
        const std::uint32_t dd = tour.step(c, forward);
        if (c == b || dd == a) continue;
        if (dab + d(c, dd) - dac - d(b, dd) > eps) {
          tour.two_opt_move(a, b, c, dd);
          for (const std::uint32_t v : {a, b, c, dd}) push(v);
          return true;
        }
      }
    }
    return false;
  };

  // Or-opt: segment s[0..len) taken from between p and q and put between x
  // and y = step(x), either way round; done as two or three 2-opt moves.
  auto try_or_opt = [&](std::uint32_t a) {
    for (const bool forward : {true, false}) {
      std::uint32_t s[3] = {a, a, a};
      for (std::size_t len = 1; len <= 3; ++len) {
        if (len > 1) s[len - 1] = tour.step(s[len - 2], forward);
        const std::uint32_t first = s[0], last = s[len - 1];
        const std::uint32_t p = tour.step(first, !forward), q = tour.step(last, forward);
        if (p == last || q == first || p == q) break;  // tour too short for this segment
        const double removed = d(p, first) + d(last, q) - d(p, q);
        if (removed <= eps) continue;
        auto in_segment = [&](std::uint32_t v) { return std::find(s, s + len, v) != s + len; };
        double best_gain = eps;
        std::uint32_t best_x = 0, best_y = 0;
        bool best_keep = false;  // true: x first ... last y; false: x last ... first y
        auto consider = [&](std::uint32_t x, std::uint32_t y, bool keep) {
          if (in_segment(x) || in_segment(y) || x == q || y == p) return;
          const double added =
              keep ? d(x, first) + d(last, y) - d(x, y) : d(x, last) + d(first, y) - d(x, y);
          if (removed - added > best_gain) {
            best_gain = removed - added;
            best_x = x;
            best_y = y;
            best_keep = keep;
          }
        };
        for (const bool from_first : {true, false}) {
          const std::uint32_t end = from_first ? first : last;
          for (std::size_t t = 0; t < nn.k; ++t) {
            const std::uint32_t c = nn.of(end)[t];
            if (d(end, c) >= removed) break;
            // c becomes the neighbour of `end`, on either side of it.
            consider(c, tour.step(c, forward), from_first);
            consider(tour.step(c, !forward), c, !from_first);
          }
        }
        if (best_gain > eps) {
          const std::uint32_t x = best_x, y = best_y;
          tour.two_opt_move(p, first, x, y);  // p x ... q last ... first y
          tour.two_opt_move(p, x, q, last);   // p q ... x last ... first y
          if (best_keep && len > 1) tour.two_opt_move(x, last, first, y);  // x first ... last y
          for (const std::uint32_t v : {p, q, x, y}) push(v);
          for (std::size_t k = 0; k < len; ++k) push(s[k]);
          return true;
        }
      }
    }
    return false;
  };

  std::size_t moves = 0;
  while (head < queue.size()) {
    if (moves >= max_moves) {
      result.hit_move_limit = true;
      break;
    }
    const std::uint32_t a = queue[head++];
    queued[a] = 0;
    if (try_two_opt(a)) {
      ++result.two_opt_moves;
      ++moves;
      push(a);
    } else if (try_or_opt(a)) {
      ++result.or_opt_moves;
      ++moves;
      push(a);
    }
    // Reclaim the consumed part of the queue now and then.
    if (head > n && head * 2 > queue.size()) {
      queue.erase(queue.begin(), queue.begin() + static_cast<std::ptrdiff_t>(head));
      head = 0;
    }
  }
  return result;
}

void cut_at_longest_edge(const float* points, std::size_t dims, Permutation& order) {
  const std::size_t n = order.size();
  if (n < 3) return;
  std::size_t cut = 0;
  double longest = -1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double e = distance(points, dims, order[i], order[(i + 1) % n]);
    if (e > longest) {
      longest = e;
      cut = i;
    }
  }
  std::rotate(order.begin(), order.begin() + static_cast<std::ptrdiff_t>((cut + 1) % n),
              order.end());
}

}  // namespace bounce
