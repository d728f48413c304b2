#include "compress/ordering_quads.h"

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

namespace bounce {
namespace {

constexpr std::size_t kQuad = 4;

// Quads of a path with their sketch sums, plus for each quad q the 4 x 4
// tables of changes "member a of q out, member b of q -1 / q +1 in" that the
// chain moves read.
class Quads {
 public:
  using Table = std::array<std::array<double, kQuad>, kQuad>;

  Quads(const float* points, std::size_t dims, Permutation& order)
      : x_(points),
        dims_(dims),
        n_(order.size()),
        count_((order.size() + kQuad - 1) / kQuad),
        order_(order),
        pos_(order.size()),
        norm2_(order.size()),
        sum_(count_ * dims, 0.0),
        toward_next_(count_),
        toward_prev_(count_) {
    for (std::size_t i = 0; i < n_; ++i) {
      pos_[order_[i]] = static_cast<std::uint32_t>(i);
      const float* p = point(order_[i]);
      double s = 0.0;
      for (std::size_t t = 0; t < dims_; ++t) {
        s += static_cast<double>(p[t]) * p[t];
        sum_[(i / kQuad) * dims_ + t] += p[t];
      }
      norm2_[order_[i]] = s;
    }
    for (std::size_t q = 0; q < count_; ++q) refresh_tables(q);
  }

  std::size_t count() const { return count_; }
  std::size_t size(std::size_t q) const { return std::min(n_, (q + 1) * kQuad) - q * kQuad; }
  std::uint32_t member(std::size_t q, std::size_t slot) const { return order_[q * kQuad + slot]; }
  std::size_t quad_of(std::uint32_t v) const { return pos_[v] / kQuad; }

  // Change of quad q's objective when its member `out` is replaced by `in`.
  double change(std::size_t q, std::uint32_t out, std::uint32_t in) const {
    const float* xo = point(out);
    const float* xi = point(in);
    const double* s = sum_.data() + q * dims_;
    double cross = 0.0, sq = 0.0;
    for (std::size_t t = 0; t < dims_; ++t) {
      const double e = static_cast<double>(xi[t]) - xo[t];
      cross += s[t] * e;
      sq += e * e;
    }
    return (norm2_[in] - norm2_[out]) - (2.0 * cross + sq) / static_cast<double>(size(q));
  }

  // Member a of q out, member b of the next (forward) or previous quad in.
  const Table& table(std::size_t q, bool forward) const {
    return forward ? toward_next_[q] : toward_prev_[q];
  }

  std::uint32_t position(std::uint32_t v) const { return pos_[v]; }

  // Puts `in` at `position` (in another quad), updating the sums. A move
  // places every element of its cycle first (positions still those before
  // the move), then commits.
  void place(std::uint32_t in, std::uint32_t position) {
    const std::size_t from = pos_[in] / kQuad, to = position / kQuad;
    const float* p = point(in);
    for (std::size_t t = 0; t < dims_; ++t) {
      sum_[to * dims_ + t] += p[t];
      sum_[from * dims_ + t] -= p[t];
    }
    order_[position] = in;
  }
  // Ends a move that changed quads lo..hi: their positions, and the tables
  // of those quads and of their neighbours.
  void commit(std::size_t lo, std::size_t hi) {
    for (std::size_t q = lo; q <= hi; ++q)
      for (std::size_t i = q * kQuad; i < q * kQuad + size(q); ++i)
        pos_[order_[i]] = static_cast<std::uint32_t>(i);
    const std::size_t a = lo > 0 ? lo - 1 : 0, b = std::min(count_ - 1, hi + 1);
    for (std::size_t q = a; q <= b; ++q) refresh_tables(q);
  }

 private:
  const float* point(std::uint32_t v) const { return x_ + std::size_t{v} * dims_; }

  void refresh_tables(std::size_t q) {
    for (const bool forward : {true, false}) {
      Table& t = forward ? toward_next_[q] : toward_prev_[q];
      for (auto& row : t) row.fill(std::numeric_limits<double>::infinity());
      if (forward ? q + 1 >= count_ : q == 0) continue;
      const std::size_t other = forward ? q + 1 : q - 1;
      for (std::size_t a = 0; a < size(q); ++a)
        for (std::size_t b = 0; b < size(other); ++b)
          t[a][b] = change(q, member(q, a), member(other, b));
    }
  }

  const float* x_;
  std::size_t dims_, n_, count_;
  Permutation& order_;
  std::vector<std::uint32_t> pos_;
  std::vector<double> norm2_, sum_;
  std::vector<Table> toward_next_, toward_prev_;
};

}  // namespace

double quad_cost(const float* points, std::size_t dims, const Permutation& order) {
  const std::size_t n = order.size();
  double cost = 0.0;
  std::vector<double> mean(dims);
  for (std::size_t g0 = 0; g0 < n; g0 += kQuad) {
    const std::size_t g1 = std::min(n, g0 + kQuad);
    std::fill(mean.begin(), mean.end(), 0.0);
    for (std::size_t i = g0; i < g1; ++i)
      for (std::size_t t = 0; t < dims; ++t) mean[t] += points[std::size_t{order[i]} * dims + t];
    for (double& m : mean) m /= static_cast<double>(g1 - g0);
    for (std::size_t i = g0; i < g1; ++i)
      for (std::size_t t = 0; t < dims; ++t) {
        const double e = points[std::size_t{order[i]} * dims + t] - mean[t];
        cost += e * e;
      }
  }
  return cost;
}

QuadRefinement refine_quads(const float* points, std::size_t dims, const NeighbourLists& nn,
                            Permutation& order, std::size_t max_passes, std::size_t max_chain) {
  const std::size_t n = order.size();
  QuadRefinement result;
  result.cost_before = result.cost_after = quad_cost(points, dims, order);
  if (n <= kQuad || max_passes == 0) return result;

  Quads quads(points, dims, order);
  // Gains below a tiny fraction of the objective are rounding: never chase them.
  const double eps = 1e-12 * std::max(result.cost_before, 1e-30);

  // Swap a with the best member of the quad of one of its neighbours.
  auto try_swap = [&](std::uint32_t a) {
    const std::size_t qa = quads.quad_of(a);
    double best = -eps;
    std::uint32_t best_c = a;
    for (std::size_t t = 0; t < nn.k; ++t) {
      const std::size_t qb = quads.quad_of(nn.of(a)[t]);
      if (qb == qa) continue;
      for (std::size_t m = 0; m < quads.size(qb); ++m) {
        const std::uint32_t c = quads.member(qb, m);
        const double change = quads.change(qa, a, c) + quads.change(qb, c, a);
        if (change < best) {
          best = change;
          best_c = c;
        }
      }
    }
    if (best_c == a) return false;
    const std::size_t qc = quads.quad_of(best_c);
    const std::uint32_t pa = quads.position(a), pc = quads.position(best_c);
    quads.place(best_c, pa);
    quads.place(a, pc);
    quads.commit(qa, qa);
    quads.commit(qc, qc);
    return true;
  };

  // Chain: a leaves quad q_0 for quad q_L (q_k = q_0 + k or q_0 - k); quad
  // q_k hands member p_k on to q_{k-1}. DP over the chain: cur[m] = best
  // change of quads q_0..q_{L-1} given p_L = member m of q_L;
  // back[direction][L][m] = slot of p_{L-1} in q_{L-1}.
  std::vector<std::array<std::uint8_t, kQuad>> back[2] = {
      std::vector<std::array<std::uint8_t, kQuad>>(max_chain + 1),
      std::vector<std::array<std::uint8_t, kQuad>>(max_chain + 1)};
  auto try_chain = [&](std::uint32_t a) {
    const std::size_t q0 = quads.quad_of(a);
    double best = -eps;
    std::size_t best_l = 0, best_slot = 0;
    bool best_forward = true;
    for (const bool forward : {true, false}) {
      auto quad_at = [&](std::size_t k) { return forward ? q0 + k : q0 - k; };
      auto& bk = back[forward ? 0 : 1];
      const std::size_t max_l = std::min(max_chain, forward ? quads.count() - 1 - q0 : q0);
      if (max_l == 0) continue;
      std::array<double, kQuad> cur;
      cur.fill(std::numeric_limits<double>::infinity());
      const std::size_t q1 = quad_at(1);
      for (std::size_t m = 0; m < quads.size(q1); ++m)
        cur[m] = quads.change(q0, a, quads.member(q1, m));
      for (std::size_t l = 1;; ++l) {
        const std::size_t ql = quad_at(l);
        for (std::size_t m = 0; m < quads.size(ql); ++m) {
          const double total = cur[m] + quads.change(ql, quads.member(ql, m), a);
          if (total < best) {
            best = total;
            best_l = l;
            best_slot = m;
            best_forward = forward;
          }
        }
        if (l == max_l) break;
        const Quads::Table& t = quads.table(ql, forward);
        const std::size_t qn = quad_at(l + 1);
        std::array<double, kQuad> next;
        next.fill(std::numeric_limits<double>::infinity());
        for (std::size_t b = 0; b < quads.size(qn); ++b)
          for (std::size_t m = 0; m < quads.size(ql); ++m)
            if (cur[m] + t[m][b] < next[b]) {
              next[b] = cur[m] + t[m][b];
              bk[l + 1][b] = static_cast<std::uint8_t>(m);
            }
        cur = next;
      }
    }
    if (best_l == 0) return false;
    auto quad_at = [&](std::size_t k) { return best_forward ? q0 + k : q0 - k; };
    const auto& bk = back[best_forward ? 0 : 1];
    // p_L..p_1 from the table, with their positions before the move.
    std::vector<std::uint32_t> p(best_l + 1), where(best_l + 1);
    p[0] = a;
    for (std::size_t k = best_l, slot = best_slot; k >= 1; --k) {
      p[k] = quads.member(quad_at(k), slot);
      if (k > 1) slot = bk[k][slot];
    }
    for (std::size_t k = 0; k <= best_l; ++k) where[k] = quads.position(p[k]);
    quads.place(a, where[best_l]);
    for (std::size_t k = 1; k <= best_l; ++k) quads.place(p[k], where[k - 1]);
    quads.commit(std::min(q0, quad_at(best_l)), std::max(q0, quad_at(best_l)));
    return true;
  };

  for (std::size_t pass = 0; pass < max_passes; ++pass) {
    ++result.passes;
    std::size_t moves = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (nn.k > 0 && try_swap(order[i])) {
        ++result.swaps;
        ++moves;
      }
      if (max_chain > 0 && try_chain(order[i])) {
        ++result.chains;
        ++moves;
      }
    }
    if (moves == 0) break;
  }
  // Re-measured rather than accumulated: the report then holds no drift.
  result.cost_after = quad_cost(points, dims, order);
  return result;
}

}  // namespace bounce
