// The frame graph and its transient allocator (runtime/frame_graph.h,
// transient_allocator.h): no two buffers live at the same time share memory,
// the peak meets the max-live lower bound for equal sizes, and a graph
// computes the same with and without aliasing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/random.h"
#include "runtime/frame_graph.h"
#include "runtime/transient_allocator.h"

namespace bounce {
namespace {

std::vector<TransientLifetime> random_lifetimes(Rng& rng, bool equal_sizes) {
  const std::size_t passes = 1 + rng.next() % 12, count = 1 + rng.next() % 20;
  std::vector<TransientLifetime> l(count);
  for (auto& x : l) {
    const std::size_t a = rng.next() % passes, b = rng.next() % passes;
    x.first = std::min(a, b);
    x.last = std::max(a, b);
    x.bytes = equal_sizes ? 1000 : 1 + rng.next() % 5000;
  }
  return l;
}

void expect_no_live_overlap(const std::vector<TransientLifetime>& l, const TransientPlacement& p,
                            std::size_t alignment) {
  ASSERT_EQ(p.offsets.size(), l.size());
  const auto end = [&](std::size_t i) {
    return p.offsets[i] + (l[i].bytes + alignment - 1) / alignment * alignment;
  };
  for (std::size_t i = 0; i < l.size(); ++i) {
    EXPECT_EQ(p.offsets[i] % alignment, 0u);
    EXPECT_LE(end(i), p.peak);
    for (std::size_t j = i + 1; j < l.size(); ++j) {
      const bool live_together = l[i].first <= l[j].last && l[j].first <= l[i].last;
      const bool share_memory = p.offsets[i] < end(j) && p.offsets[j] < end(i);
      EXPECT_FALSE(live_together && share_memory) << "buffers " << i << " and " << j;
    }
  }
}

TEST(FrameGraph, AllocatorNeverOverlapsLiveBuffers) {
  Rng rng(42, 0);
  for (int trial = 0; trial < 500; ++trial) {
    const auto l = random_lifetimes(rng, false);
    for (std::size_t alignment : {std::size_t{1}, std::size_t{256}}) {
      const TransientPlacement p = place_transients(l, alignment);
      expect_no_live_overlap(l, p, alignment);
      EXPECT_GE(p.peak, max_live_bytes(l, alignment));
      EXPECT_LE(p.peak, total_bytes(l, alignment));
    }
  }
}

TEST(FrameGraph, EqualSizesReachTheMaxLiveBound) {
  Rng rng(7, 0);
  for (int trial = 0; trial < 500; ++trial) {
    const auto l = random_lifetimes(rng, true);
    const TransientPlacement p = place_transients(l, 8);
    expect_no_live_overlap(l, p, 8);
    EXPECT_EQ(p.peak, max_live_bytes(l, 8)) << "trial " << trial;
  }
}

TEST(FrameGraph, RejectsBadInput) {
  EXPECT_THROW(place_transients({{3, 2, 10}}), Error);
  EXPECT_THROW(place_transients({{0, 2, 10}}, 0), Error);
  FrameGraph g;
  const auto a = g.add_transient("a", 16);
  g.add_pass("reads a first", {a}, {}, {});
  EXPECT_THROW(g.compile(true), Error);
  FrameGraph unused;
  unused.add_transient("never", 16);
  EXPECT_THROW(unused.compile(true), Error);
  EXPECT_THROW(g.add_pass("unknown", {5}, {}, {}), Error);
}

// A chain x -> a = x + 1 -> b = 2 a -> c = b - 3 -> d = c^2 -> out = d + a:
// a is read by the last pass, so it keeps its memory throughout; b is dead
// once c is written, so d can take b's memory. Same result both ways, three
// buffers instead of four.
TEST(FrameGraph, ExecutesTheSameWithAndWithoutAliasing) {
  const std::size_t n = 100;
  std::vector<float> x(n), out_alias(n), out_plain(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = static_cast<float>(i);
  for (bool alias : {true, false}) {
    std::vector<float>& out = alias ? out_alias : out_plain;
    FrameGraph g;
    const std::size_t bytes = n * sizeof(float);
    const auto in = g.add_imported("x", x.data(), bytes);
    const auto result = g.add_imported("out", out.data(), bytes);
    const auto a = g.add_transient("a", bytes);
    const auto b = g.add_transient("b", bytes);
    const auto c = g.add_transient("c", bytes);
    const auto d = g.add_transient("d", bytes);
    const auto map = [n](FrameGraph::ResourceId from, FrameGraph::ResourceId to, auto f) {
      return [=](const FrameGraph::Context& ctx) {
        const float* s = ctx.get<float>(from);
        float* t = ctx.get<float>(to);
        for (std::size_t i = 0; i < n; ++i) t[i] = f(s[i]);
      };
    };
    g.add_pass("a", {in}, {a}, map(in, a, [](float v) { return v + 1.0f; }));
    g.add_pass("b", {a}, {b}, map(a, b, [](float v) { return 2.0f * v; }));
    g.add_pass("c", {b}, {c}, map(b, c, [](float v) { return v - 3.0f; }));
    g.add_pass("d", {c}, {d}, map(c, d, [](float v) { return v * v; }));
    g.add_pass("out", {d, a}, {result}, [=](const FrameGraph::Context& ctx) {
      for (std::size_t i = 0; i < n; ++i)
        ctx.get<float>(result)[i] = ctx.get<float>(d)[i] + ctx.get<float>(a)[i];
    });
    g.compile(alias, 64);
    g.execute();
    EXPECT_EQ(g.unaliased_transient_bytes(), 4 * 448u);
    // a lives throughout; b, c, d each overlap only their neighbours.
    EXPECT_EQ(g.transient_bytes(), alias ? 3 * 448u : 4 * 448u);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const float a = x[i] + 1.0f, c = 2.0f * a - 3.0f;
    EXPECT_EQ(out_plain[i], c * c + a);
    EXPECT_EQ(out_alias[i], out_plain[i]);
  }
}

// Random graphs executed in the checking mode: every transient is filled with
// its own value by its first pass and checked, element by element, by every
// later pass of its lifetime; after each pass the dead transients' ranges
// are overwritten with NaN. A live buffer sharing memory with another live
// one, or with a dead one, would fail a check. The arena is exactly the
// allocator's peak.
TEST(FrameGraph, PoisonedExecutionFindsNoClobberedLiveBuffer) {
  Rng rng(2024, 0);
  for (int trial = 0; trial < 200; ++trial) {
    const auto l = random_lifetimes(rng, trial % 2 == 0);
    std::size_t passes = 0;
    for (const auto& x : l) passes = std::max(passes, x.last + 1);
    FrameGraph g;
    std::vector<FrameGraph::ResourceId> ids;
    for (std::size_t t = 0; t < l.size(); ++t)
      ids.push_back(g.add_transient("t" + std::to_string(t), l[t].bytes));
    std::size_t bad = 0, checked = 0;
    for (std::size_t p = 0; p < passes; ++p) {
      std::vector<FrameGraph::ResourceId> reads, writes;
      for (std::size_t t = 0; t < l.size(); ++t) {
        if (l[t].first == p) writes.push_back(ids[t]);
        if (l[t].first < p && p <= l[t].last) reads.push_back(ids[t]);
      }
      g.add_pass("p" + std::to_string(p), reads, writes, [&, p](const FrameGraph::Context& c) {
        for (std::size_t t = 0; t < l.size(); ++t) {
          if (l[t].first > p || p > l[t].last) continue;
          unsigned char* m = c.get<unsigned char>(ids[t]);
          const auto value = static_cast<unsigned char>(t + 1);
          if (l[t].first == p) {
            std::fill_n(m, l[t].bytes, value);
            continue;
          }
          ++checked;
          for (std::size_t i = 0; i < l[t].bytes; ++i)
            if (m[i] != value) {
              ++bad;
              break;
            }
        }
      });
    }
    g.set_poison_dead_transients(true);
    g.compile(true, 64);
    EXPECT_EQ(g.arena_bytes(), g.transient_bytes());
    EXPECT_EQ(g.transient_bytes(), place_transients(l, 64).peak);
    g.execute();
    EXPECT_EQ(bad, 0u) << "trial " << trial << ", " << checked << " checks";
  }
}

// The checking mode can fail: a pass that reads a transient after its
// declared lifetime (an undeclared read) gets the NaN written at its death.
TEST(FrameGraph, PoisonShowsAReadAfterTheLifetime) {
  FrameGraph g;
  float out = 0.0f;
  const auto result = g.add_imported("out", &out, sizeof(float));
  const auto a = g.add_transient("a", 64 * sizeof(float));
  g.add_pass("write a", {}, {a},
             [a](const FrameGraph::Context& c) { std::fill_n(c.get<float>(a), 64, 1.0f); });
  g.add_pass("read a, undeclared", {}, {result}, [a, result](const FrameGraph::Context& c) {
    *c.get<float>(result) = c.get<float>(a)[7];
  });
  g.compile(true);
  g.execute();
  EXPECT_EQ(out, 1.0f);  // unchecked: the stale value goes unnoticed
  g.set_poison_dead_transients(true);
  g.execute();
  EXPECT_TRUE(std::isnan(out));
}

TEST(FrameGraph, DynamicRadiosityGraphAliasesTheLocalUpdate) {
  for (bool temporal : {false, true}) {
    FrameGraph g = dynamic_radiosity_memory_graph(1736, 3, temporal);
    g.compile(true, 256);
    // Local-matrix vectors (4 x 3 floats per patch) end before E and B
    // (2 x vec3 per patch) begin: the arena holds the larger group only.
    const std::size_t local = 4 * ((1736 * 12 + 255) / 256 * 256);
    const std::size_t light = 2 * ((1736 * 12 + 255) / 256 * 256);
    EXPECT_EQ(g.unaliased_transient_bytes(), local + light);
    EXPECT_EQ(g.transient_bytes(), std::max(local, light));
    EXPECT_EQ(g.transient_bytes(), g.max_live_transient_bytes());
  }
}

}  // namespace
}  // namespace bounce
