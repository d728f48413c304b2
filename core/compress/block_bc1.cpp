#include "compress/block_bc1.h"

#include <squish.h>

#include <algorithm>
#include <cmath>
#include <cstring>  // stb_dxt.h calls memcpy without including <string.h>
#include <limits>
#include <string>

#include "base/error.h"

// The one translation unit that holds stb_dxt's code (block_bc4.cpp only
// declares its functions).
#define STB_DXT_IMPLEMENTATION
#include <stb/stb_dxt.h>

namespace bounce {

namespace {

// ---------------------------------------------------------------------------
// Format helpers

inline int expand5(int q) { return (q << 3) | (q >> 2); }
inline int expand6(int q) { return (q << 2) | (q >> 4); }
inline int pack565(const int q[3]) { return (q[0] << 11) | (q[1] << 5) | q[2]; }

void unpack565(int value, int rgb[3]) {
  rgb[0] = expand5((value >> 11) & 0x1f);
  rgb[1] = expand6((value >> 5) & 0x3f);
  rgb[2] = expand5(value & 0x1f);
}

// Tables computed once (thread-safe static initialisation).
struct Tables {
  // Single-colour fits: endpoints (qa, qb) whose 1/3 point (four-colour,
  // mode 0) or midpoint (three-colour, mode 1) is nearest to x, and that
  // distance. Same idea as libsquish's single-colour lookup, computed here
  // instead of shipped as data. Index [mode][bits == 6][x].
  struct Entry {
    std::uint8_t qa, qb;
    float err;  // |decoded - x|
  };
  Entry single[2][2][256];

  Tables() {
    for (int six = 0; six < 2; ++six) {
      const int maxq = six ? 63 : 31;
      auto ex = [six](int q) { return six ? expand6(q) : expand5(q); };
      for (int x = 0; x < 256; ++x) {
        for (int mode = 0; mode < 2; ++mode) {
          int best = 1 << 20;
          for (int qa = 0; qa <= maxq; ++qa) {
            for (int qb = 0; qb <= maxq; ++qb) {
              const int ea = ex(qa), eb = ex(qb);
              const int v = mode == 0 ? (2 * ea + eb) / 3 : (ea + eb) / 2;
              // Error first, then the spread of the endpoints (a tighter
              // pair is as good and keeps the other levels near the colour).
              const int score = std::abs(v - x) * 1024 + std::abs(ea - eb);
              if (score < best) {
                best = score;
                single[mode][six][x] = {static_cast<std::uint8_t>(qa),
                                        static_cast<std::uint8_t>(qb),
                                        static_cast<float>(std::abs(v - x))};
              }
            }
          }
        }
      }
    }
  }
};

const Tables& tables() {
  static const Tables t;
  return t;
}

// ---------------------------------------------------------------------------
// The weighted encoder.
//
// Why this design: the error is a per-channel weighted least-squares problem
// whose weights span decades within a block (weight ~ value^2 and one code
// step is a 10% value step), and the loss of BC1 on this data is dominated
// by endpoint quantisation. So:
//  1. Identical colours are merged (their weights add up): smooth blocks of
//     the matrix hold few distinct colours (on the benchmark matrix 1-3 in
//     95% of blocks), which makes every later step cheap.
//  2. Cluster fit (as libsquish) over the points ordered along the weighted
//     principal axis, but solving the 2x2 least-squares problem per channel
//     with per-channel weights, so heavy texels and channels count as much as
//     they cost after decoding and holes not at all.
//  3. The levels of the best partition are refined: given the levels, the
//     error separates into three independent one-channel problems, so the
//     endpoints are quantised per channel by an exact search (both 5/6-bit
//     codes around the least-squares a, and for each the two codes around
//     the conditional optimum of b), scored with the decoder's exact integer
//     palette through per-level weight sums (4 terms per candidate, not 16).
//     Then each point takes its best level for the quantised palette, and
//     the two steps repeat while the levels change and the error falls.
//  4. Quantisation makes ties of the continuous fit matter: two colours fit
//     exactly with any two levels, but {1/3, 2/3} hits 565-quantised targets
//     far more often than {0, 1} (the endpoints may straddle them). So two
//     colours try the useful level pairs, a near-tied second partition is
//     refined too, and three-colour mode (midpoint, and black = code 0 for
//     zeros) is tried from its own cluster fit. One colour uses exact tables.
// Every candidate is scored with its exact decoded error and the best kept.
// The three channels are processed together as the lanes of 4-float vectors
// (GCC/Clang vector extensions, plain SSE2 on x86-64), which made the search
// as fast as libsquish's cluster fit on smooth data. The decoder's integer
// arithmetic is reproduced exactly in float: an integer n divided by d has a
// fraction k/d, so trunc((n + 0.5) * (1/d)) stays within [1/(2d), 1 - 1/(2d)]
// of the right integer, far beyond the rounding of the reciprocal (values
// are below 2^10); bit replication is q * 33/4 or q * 65/16, exact in float.
// (All codes and endpoint pairs were also checked exhaustively.)

using F4 = float __attribute__((vector_size(16)));
using I4 = int __attribute__((vector_size(16)));

inline F4 splat(float x) { return F4{x, x, x, x}; }
inline F4 trunc4(F4 x) { return __builtin_convertvector(__builtin_convertvector(x, I4), F4); }
inline F4 min4(F4 a, F4 b) { return a < b ? a : b; }
inline F4 max4(F4 a, F4 b) { return a > b ? a : b; }
inline float hsum3(F4 v) { return v[0] + v[1] + v[2]; }
// 1/x to ~23 bits: the hardware estimate and one Newton step where SSE has
// one (the results only seed an exact search, so full division is not needed).
inline F4 recip4(F4 x) {
#if defined(__SSE__) && !defined(BOUNCE_EXACT_RECIP)
  const F4 r = __builtin_ia32_rcpps(x);
  return r * (2.0f - x * r);
#else
  return 1.0f / x;
#endif
}

// Per-lane constants: R and B have 5 bits, G 6; lane 3 is unused (weight 0).
const F4 kMaxQ4 = {31.0f, 63.0f, 31.0f, 0.0f};
const F4 kExpand4 = {8.25f, 4.0625f, 8.25f, 0.0f};  // q*33/4, q*65/16: bit replication
const F4 kFloorMul4 = {4.0f, 16.0f, 4.0f, 0.0f};
const F4 kFloorAdd4 = {3.5f, 15.5f, 3.5f, 0.0f};
const F4 kFloorInv4 = {1.0f / 33.0f, 1.0f / 65.0f, 1.0f / 33.0f, 0.0f};

// Expansion of 5/6-bit codes to 8 bits.
inline F4 expand4(F4 q) { return trunc4(q * kExpand4); }
// Largest code whose expansion is <= x: floor((4x+3)/33) for 5 bits,
// floor((16x+15)/65) for 6 bits, x clamped to [0, 255] first.
inline F4 floor_q4(F4 x) {
  const F4 xi = trunc4(min4(max4(x, splat(0.0f)), splat(255.0f)));
  return trunc4((xi * kFloorMul4 + kFloorAdd4) * kFloorInv4);
}
// Decoded levels for expanded endpoints: (2a+b)/3 and (a+2b)/3, or (a+b)/2.
inline void palette4(bool four, F4 ea, F4 eb, F4 pal[4]) {
  pal[0] = ea;
  if (four) {
    const F4 third = splat(1.0f / 3.0f);
    pal[1] = trunc4((ea + ea + eb + 0.5f) * third);
    pal[2] = trunc4((ea + eb + eb + 0.5f) * third);
    pal[3] = eb;
  } else {
    pal[1] = trunc4((ea + eb) * 0.5f);
    pal[2] = eb;
    pal[3] = splat(0.0f);
  }
}

struct Points {
  int n = 0;
  F4 t[16];                    // distinct target colours (lane 3: 0)
  F4 w[16];                    // their summed weights, scaled so the largest is 1
  std::int8_t of_texel[16]{};  // point of each texel, -1 for a hole
};

inline float sanitise(float w) {
  if (!(w > 0.0f)) return 0.0f;  // negative, zero or NaN
  return std::min(w, std::numeric_limits<float>::max());
}

// Returns false when no texel has a positive weight.
bool gather(const std::uint8_t rgb[16][3], const float weight[16][3], Points& p) {
  // The 48 weights as 12 vectors: negative and NaN weights count as 0 (NaN
  // fails the comparison), infinite ones as the largest float.
  float w[48];
  F4 wmax = splat(0.0f);
  for (int k = 0; k < 12; ++k) {
    F4 raw;
    std::memcpy(&raw, &weight[0][0] + 4 * k, sizeof raw);
    raw = raw > 0.0f ? min4(raw, splat(std::numeric_limits<float>::max())) : splat(0.0f);
    wmax = max4(wmax, raw);
    std::memcpy(w + 4 * k, &raw, sizeof raw);
  }
  const float top = std::max({wmax[0], wmax[1], wmax[2], wmax[3]});
  if (!(top > 0.0f)) return false;
  const float scale = 1.0f / top;
  int keys[16];
  p.n = 0;
  for (int i = 0; i < 16; ++i) {
    const F4 wi = F4{w[3 * i], w[3 * i + 1], w[3 * i + 2], 0.0f};
    if (!(wi[0] + wi[1] + wi[2] > 0.0f)) {
      p.of_texel[i] = -1;
      continue;
    }
    const int key = rgb[i][0] << 16 | rgb[i][1] << 8 | rgb[i][2];
    int m = 0;
    while (m < p.n && keys[m] != key) ++m;
    if (m == p.n) {
      keys[m] = key;
      p.t[m] = F4{static_cast<float>(rgb[i][0]), static_cast<float>(rgb[i][1]),
                  static_cast<float>(rgb[i][2]), 0.0f};
      p.w[m] = splat(0.0f);
      ++p.n;
    }
    p.w[m] += wi * scale;
    p.of_texel[i] = static_cast<std::int8_t>(m);
  }
  return true;
}

// Levels of all points, 2 bits each (point m at bits 2m): cheap to copy and
// compare, so repeated starting points are skipped.
using Levels = std::uint32_t;
inline int level_of(Levels levels, int m) { return static_cast<int>(levels >> (2 * m)) & 3; }

struct Candidate {
  bool four = true;
  F4 qa{}, qb{};  // quantised endpoints a and b, per channel lane
  Levels levels = 0;
  float err = std::numeric_limits<float>::infinity();
};

// Each point's best level for the quantised endpoints; returns the total error.
float assign_levels(const Points& p, bool four, F4 qa, F4 qb, Levels& levels) {
  // One vector per channel holding its four levels, computed as
  // trunc((a alpha' + b beta' + bias) * scale), which gives exactly a,
  // (2a+b)/3, (a+2b)/3, b or a, (a+b)/2, b, 0 (alpha', beta' integers).
  const F4 ea = expand4(qa), eb = expand4(qb);
  const F4 ka = four ? F4{3.0f, 2.0f, 1.0f, 0.0f} : F4{2.0f, 1.0f, 0.0f, 0.0f};
  const F4 kb = four ? F4{0.0f, 1.0f, 2.0f, 3.0f} : F4{0.0f, 1.0f, 2.0f, 0.0f};
  const F4 bias = splat(four ? 0.5f : 0.0f), scale = splat(four ? 1.0f / 3.0f : 0.5f);
  F4 by_level[3];
  for (int c = 0; c < 3; ++c) by_level[c] = trunc4((ea[c] * ka + eb[c] * kb + bias) * scale);
  float total = 0.0f;
  Levels out = 0;
  for (int m = 0; m < p.n; ++m) {
    const F4 d0 = by_level[0] - p.t[m][0], d1 = by_level[1] - p.t[m][1],
             d2 = by_level[2] - p.t[m][2];
    const F4 e = p.w[m][0] * d0 * d0 + p.w[m][1] * d1 * d1 + p.w[m][2] * d2 * d2;
    int best_l = 0;
    for (int l = 1; l < 4; ++l)
      if (e[l] < e[best_l]) best_l = l;
    out |= static_cast<Levels>(best_l) << (2 * m);
    total += e[best_l];
  }
  levels = out;
  return total;
}

// Best quantised endpoints for fixed levels, every channel at once.
void fit_endpoints(const Points& p, bool four, Levels levels, F4& qa_out, F4& qb_out) {
  // Per-level sums: the error of a palette is sum_l (W_l pal_l - 2 X_l) pal_l
  // plus a constant.
  F4 wl[4] = {}, xl[4] = {};
  for (int m = 0; m < p.n; ++m) {
    const int l = level_of(levels, m);
    wl[l] += p.w[m];
    xl[l] += p.w[m] * p.t[m];
  }
  // Normal equations of sum_l W_l (alpha_l a + beta_l b - t)^2 with
  // alpha, beta = (1, 0), (2/3, 1/3), (1/3, 2/3), (0, 1) or, for three
  // colours, (1, 0), (1/2, 1/2), (0, 1) and black (0, 0).
  F4 aa, bb, ab, da, db;
  if (four) {
    aa = wl[0] + (4.0f / 9.0f) * wl[1] + (1.0f / 9.0f) * wl[2];
    bb = (1.0f / 9.0f) * wl[1] + (4.0f / 9.0f) * wl[2] + wl[3];
    ab = (2.0f / 9.0f) * (wl[1] + wl[2]);
    da = xl[0] + (2.0f / 3.0f) * xl[1] + (1.0f / 3.0f) * xl[2];
    db = (1.0f / 3.0f) * xl[1] + (2.0f / 3.0f) * xl[2] + xl[3];
  } else {
    aa = wl[0] + 0.25f * wl[1];
    bb = 0.25f * wl[1] + wl[2];
    ab = 0.25f * wl[1];
    da = xl[0] + 0.5f * xl[1];
    db = 0.5f * xl[1] + xl[2];
  }
  // Continuous least squares; a nearly singular system means (almost) all
  // weight sits on one level, where the best line is the weighted mean.
  // (Lanes without weight compute garbage that no choice depends on.)
  const F4 det = aa * bb - ab * ab;
  const auto solvable = det > 1e-5f * aa * bb && aa > 0.0f && bb > 0.0f;
  const F4 inv_det = recip4(solvable ? det : splat(1.0f));
  F4 a = (bb * da - ab * db) * inv_det;
  F4 b = (aa * db - ab * da) * inv_det;
  if (!(solvable[0] && solvable[1] && solvable[2])) {
    const F4 wsum = wl[0] + wl[1] + wl[2] + (four ? wl[3] : splat(0.0f));
    const F4 xsum = xl[0] + xl[1] + xl[2] + (four ? xl[3] : splat(0.0f));
    const F4 mean = xsum / (wsum > 0.0f ? wsum : splat(1.0f));
    a = solvable ? a : mean;
    b = solvable ? b : mean;
  }
  const auto b_free = bb > 0.0f;
  const F4 inv_bb = recip4(b_free ? bb : splat(1.0f));
  auto error_of = [&](F4 ea, F4 eb) {
    F4 pal[4];
    palette4(four, ea, eb, pal);
    return (wl[0] * pal[0] - 2.0f * xl[0]) * pal[0] + (wl[1] * pal[1] - 2.0f * xl[1]) * pal[1] +
           (wl[2] * pal[2] - 2.0f * xl[2]) * pal[2] + (wl[3] * pal[3] - 2.0f * xl[3]) * pal[3];
  };
  // The codes either side of a; for each, the codes either side of the b
  // that minimises the error for that a (b itself where b carries no
  // weight). Wider windows changed the error by < 0.5% in tests.
  F4 best = splat(std::numeric_limits<float>::infinity());
  F4 best_qa{}, best_qb{};
  const F4 qa0 = floor_q4(a);
  for (const F4 qa : {qa0, min4(qa0 + 1.0f, kMaxQ4)}) {
    const F4 ea = expand4(qa);
    const F4 bstar = b_free ? (db - ab * ea) * inv_bb : b;
    const F4 qb0 = floor_q4(bstar);
    for (const F4 qb : {qb0, min4(qb0 + 1.0f, kMaxQ4)}) {
      const F4 e = error_of(ea, expand4(qb));
      const auto better = e < best;
      best = better ? e : best;
      best_qa = better ? qa : best_qa;
      best_qb = better ? qb : best_qb;
    }
  }
  qa_out = best_qa;
  qb_out = best_qb;
}

// Search state of one block: the level sets already fitted (per mode), so
// ties, variants and iterations that coincide cost nothing, and the error
// below which the search stops.
struct Search {
  Levels levels[32];
  bool four[32];
  int count = 0;
  float good_enough = 0.0f;
  bool add(bool four_mode, Levels l) {
    for (int k = 0; k < count; ++k)
      if (levels[k] == l && four[k] == four_mode) return false;
    if (count < 32) {
      levels[count] = l;
      four[count] = four_mode;
      ++count;
    }
    return true;
  }
};

// Rounds of (fit endpoints, assign levels) per start; in practice the levels
// settle after one or two.
constexpr int kIterations = 4;

// Alternates endpoint fitting and level assignment from the given levels.
void refine(const Points& p, bool four, Levels start, Search& search, Candidate& best) {
  if (best.err <= search.good_enough || !search.add(four, start)) return;
  Candidate local, cand;
  local.four = cand.four = four;
  Levels levels = start;
  for (int it = 0; it < kIterations; ++it) {
    fit_endpoints(p, four, levels, cand.qa, cand.qb);
    cand.err = assign_levels(p, four, cand.qa, cand.qb, cand.levels);
    if (!(cand.err < local.err)) break;
    local = cand;
    // Levels fitted before (now or from another start) would give the same
    // endpoints again.
    if (cand.err <= 0.0f || cand.levels == levels || !search.add(four, cand.levels)) break;
    levels = cand.levels;
  }
  if (local.err < best.err) best = local;
}

// Order of the points along the principal axis of their weighted covariance
// (each channel pair weighted by sqrt(w_c w_d), so unimportant channels do not
// steer the axis).
void principal_order(const Points& p, int order[16]) {
  F4 wsum{}, xsum{};
  for (int m = 0; m < p.n; ++m) {
    wsum += p.w[m];
    xsum += p.w[m] * p.t[m];
  }
  const F4 mean = xsum / (wsum > 0.0f ? wsum : splat(1.0f));
  float cov[3][3] = {};
  for (int m = 0; m < p.n; ++m) {
    const F4 sd = F4{std::sqrt(p.w[m][0]), std::sqrt(p.w[m][1]), std::sqrt(p.w[m][2]), 0.0f} *
                  (p.t[m] - mean);
    for (int c = 0; c < 3; ++c)
      for (int e = c; e < 3; ++e) cov[c][e] += sd[c] * sd[e];
  }
  cov[1][0] = cov[0][1];
  cov[2][0] = cov[0][2];
  cov[2][1] = cov[1][2];
  // Power iteration from the row of the largest variance.
  int start = 0;
  for (int c = 1; c < 3; ++c)
    if (cov[c][c] > cov[start][start]) start = c;
  float v[3] = {cov[start][0], cov[start][1], cov[start][2]};
  if (!(cov[start][start] > 0.0f)) v[0] = v[1] = v[2] = 1.0f;
  for (int it = 0; it < 8; ++it) {
    float u[3];
    for (int c = 0; c < 3; ++c) u[c] = cov[c][0] * v[0] + cov[c][1] * v[1] + cov[c][2] * v[2];
    const float norm = std::max({std::abs(u[0]), std::abs(u[1]), std::abs(u[2])});
    if (!(norm > 0.0f)) break;
    for (int c = 0; c < 3; ++c) v[c] = u[c] / norm;
  }
  float proj[16];
  for (int m = 0; m < p.n; ++m) {
    proj[m] = v[0] * p.t[m][0] + v[1] * p.t[m][1] + v[2] * p.t[m][2];
    order[m] = m;
  }
  for (int m = 1; m < p.n; ++m) {  // insertion sort, n <= 16
    const int o = order[m];
    int k = m;
    while (k > 0 && proj[order[k - 1]] > proj[o]) {
      order[k] = order[k - 1];
      --k;
    }
    order[k] = o;
  }
}

// The two best partitions of the ordered points into consecutive clusters.
struct Partition {
  float gain = -1.0f;
  int bound[3]{};
};

inline void keep_partition(Partition best[2], float gain, int i, int j, int k) {
  if (gain > best[0].gain) {
    best[1] = best[0];
    best[0] = {gain, {i, j, k}};
  } else if (gain > best[1].gain) {
    best[1] = {gain, {i, j, k}};
  }
}

// Gain of one partition, summed over channels: with A = sum w alpha^2,
// B = sum w beta^2, C = sum w alpha beta, Da = sum w alpha t, Db = sum w beta t
// it is (B Da^2 - 2 C Da Db + A Db^2) / (A B - C^2), evaluated with alpha and
// beta scaled to integers (the ratio is scale-free); 0 for singular systems.
inline float partition_gain(F4 aa, F4 bb, F4 ab, F4 da, F4 db) {
  const F4 det = aa * bb - ab * ab;
  const F4 num = bb * da * da - 2.0f * ab * da * db + aa * db * db;
  const auto ok = det > 1e-5f * aa * bb;
  const F4 gain = ok ? num / (ok ? det : splat(1.0f)) : splat(0.0f);
  return hsum3(gain);
}

// Cluster fit with per-channel weights. Points order[0, i) take level 0,
// [i, j) level 1, [j, k) level 2 and [k, n) level 3 (four colours; for three,
// k = n and [j, n) take level 2). Targets are centred on the weighted mean so
// the gain (error removed relative to the best constant) is computed without
// cancellation.
void cluster_fit(const Points& p, const int order[16], bool four, Partition best[2]) {
  const int n = p.n;
  F4 wsum{}, xsum{};
  for (int m = 0; m < n; ++m) {
    wsum += p.w[m];
    xsum += p.w[m] * p.t[m];
  }
  const F4 mean = xsum / (wsum > 0.0f ? wsum : splat(1.0f));
  F4 pw[17], px[17];
  pw[0] = px[0] = splat(0.0f);
  for (int m = 0; m < n; ++m) {
    const int o = order[m];
    pw[m + 1] = pw[m] + p.w[o];
    px[m + 1] = px[m] + p.w[o] * (p.t[o] - mean);
  }
  for (int i = 0; i <= n; ++i) {
    for (int j = i; j <= n; ++j) {
      const F4 w0 = pw[i], w1 = pw[j] - pw[i], x0 = px[i], x1 = px[j] - px[i];
      if (!four) {
        const F4 w2 = pw[n] - pw[j], x2 = px[n] - px[j];
        keep_partition(
            best,
            partition_gain(4.0f * w0 + w1, w1 + 4.0f * w2, w1, 2.0f * x0 + x1, x1 + 2.0f * x2), i,
            j, n);
        continue;
      }
      for (int k = j; k <= n; ++k) {
        const F4 w2 = pw[k] - pw[j], w3 = pw[n] - pw[k], x2 = px[k] - px[j], x3 = px[n] - px[k];
        keep_partition(
            best,
            partition_gain(9.0f * w0 + 4.0f * w1 + w2, w1 + 4.0f * w2 + 9.0f * w3, 2.0f * (w1 + w2),
                           3.0f * x0 + 2.0f * x1 + x2, x1 + 2.0f * x2 + 3.0f * x3),
            i, j, k);
      }
    }
  }
}

Levels levels_of_partition(int n, const int order[16], const Partition& part) {
  Levels levels = 0;
  for (int m = 0; m < n; ++m) {
    const Levels l = m < part.bound[0] ? 0 : m < part.bound[1] ? 1 : m < part.bound[2] ? 2 : 3;
    levels |= l << (2 * order[m]);
  }
  return levels;
}

// One colour: per channel the table's best endpoints for level 1 (the 1/3
// point or the midpoint), the mode with the smaller weighted error.
void single_colour(const Points& p, Candidate& best) {
  const Tables& t = tables();
  float err[2];
  for (int mode = 0; mode < 2; ++mode) {
    err[mode] = 0.0f;
    for (int c = 0; c < 3; ++c) {
      const float e = t.single[mode][c == 1][static_cast<int>(p.t[0][c])].err;
      err[mode] += p.w[0][c] * e * e;
    }
  }
  const int mode = err[1] < err[0] ? 1 : 0;
  best.four = mode == 0;
  best.levels = 1;  // point 0 on level 1
  best.err = err[mode];
  for (int c = 0; c < 3; ++c) {
    const Tables::Entry& e = t.single[mode][c == 1][static_cast<int>(p.t[0][c])];
    best.qa[c] = e.qa;
    best.qb[c] = e.qb;
  }
}

// When one point outweighs the others by decades (weights ~ value^2 vary
// that much within a block), the best block is often the exact single-colour
// fit of that point with the others on whatever level is nearest.
void dominant_colour(const Points& p, Candidate& best) {
  int heaviest = 0;
  float top = 0.0f;
  for (int m = 0; m < p.n; ++m) {
    const float w = hsum3(p.w[m]);
    if (w > top) {
      top = w;
      heaviest = m;
    }
  }
  const Tables& t = tables();
  for (int mode = 0; mode < 2; ++mode) {
    Candidate cand;
    cand.four = mode == 0;
    for (int c = 0; c < 3; ++c) {
      const Tables::Entry& e = t.single[mode][c == 1][static_cast<int>(p.t[heaviest][c])];
      cand.qa[c] = e.qa;
      cand.qb[c] = e.qb;
    }
    cand.err = assign_levels(p, cand.four, cand.qa, cand.qb, cand.levels);
    if (cand.err < best.err) best = cand;
  }
}

// Search stops once the error per unit weight is below the variance of the
// 8-bit rounding that the log quantiser made before BC1 (1/12 code^2): more
// search could not gain more than that noise. (Costs < 0.05% error on the
// benchmark matrix, saves ~5% time.)
constexpr float kGoodEnough = 1.0f / 12.0f;

// A second partition is refined when its continuous gain is this close to
// the best one: near-ties quantise differently, clear losers rarely win.
constexpr float kNearTie = 0.9f;

void write_block(int c0, int c1, const std::uint8_t index[16], std::uint8_t out[8]) {
  out[0] = static_cast<std::uint8_t>(c0 & 0xff);
  out[1] = static_cast<std::uint8_t>(c0 >> 8);
  out[2] = static_cast<std::uint8_t>(c1 & 0xff);
  out[3] = static_cast<std::uint8_t>(c1 >> 8);
  for (int r = 0; r < 4; ++r)
    out[4 + r] = static_cast<std::uint8_t>(index[4 * r] | index[4 * r + 1] << 2 |
                                           index[4 * r + 2] << 4 | index[4 * r + 3] << 6);
}

// Orders the endpoints as the mode requires and maps levels to indices.
void pack(const Points& p, const Candidate& cand, std::uint8_t out[8]) {
  const int qa[3] = {static_cast<int>(cand.qa[0]), static_cast<int>(cand.qa[1]),
                     static_cast<int>(cand.qa[2])};
  const int qb[3] = {static_cast<int>(cand.qb[0]), static_cast<int>(cand.qb[1]),
                     static_cast<int>(cand.qb[2])};
  int pa = pack565(qa), pb = pack565(qb);
  std::uint8_t map[4];
  if (cand.four) {
    if (pa == pb) {
      // Equal endpoints decode in three-colour mode; every level is c0 anyway.
      map[0] = map[1] = map[2] = map[3] = 0;
    } else if (pa > pb) {
      map[0] = 0, map[1] = 2, map[2] = 3, map[3] = 1;
    } else {
      std::swap(pa, pb);
      map[0] = 1, map[1] = 3, map[2] = 2, map[3] = 0;
    }
  } else if (pa <= pb) {
    map[0] = 0, map[1] = 2, map[2] = 1, map[3] = 3;
  } else {
    std::swap(pa, pb);
    map[0] = 1, map[1] = 2, map[2] = 0, map[3] = 3;
  }
  std::uint8_t index[16];
  for (int i = 0; i < 16; ++i)
    index[i] = p.of_texel[i] < 0 ? 0 : map[level_of(cand.levels, p.of_texel[i])];
  write_block(pa, pb, index, out);
}

}  // namespace

void decode_bc1_block(const std::uint8_t* block, std::uint8_t rgb[16][3]) {
  const int a = block[0] | block[1] << 8;
  const int b = block[2] | block[3] << 8;
  int pal[4][3];
  unpack565(a, pal[0]);
  unpack565(b, pal[1]);
  for (int c = 0; c < 3; ++c) {
    if (a > b) {
      pal[2][c] = (2 * pal[0][c] + pal[1][c]) / 3;
      pal[3][c] = (pal[0][c] + 2 * pal[1][c]) / 3;
    } else {
      pal[2][c] = (pal[0][c] + pal[1][c]) / 2;
      pal[3][c] = 0;
    }
  }
  for (int i = 0; i < 16; ++i) {
    const int idx = (block[4 + i / 4] >> (2 * (i % 4))) & 3;
    for (int c = 0; c < 3; ++c) rgb[i][c] = static_cast<std::uint8_t>(pal[idx][c]);
  }
}

void encode_bc1_block_weighted(const std::uint8_t rgb[16][3], const float weight[16][3],
                               std::uint8_t out[8]) {
  Points p;
  if (!gather(rgb, weight, p)) {
    // Nothing to represent: black everywhere.
    const std::uint8_t zero[16] = {};
    write_block(0, 0, zero, out);
    return;
  }
  Candidate best;
  if (p.n == 1) {
    single_colour(p, best);
  } else {
    Search search;
    F4 wtot{};
    for (int m = 0; m < p.n; ++m) wtot += p.w[m];
    search.good_enough = kGoodEnough * hsum3(wtot);
    dominant_colour(p, best);
    if (p.n == 2) {
      // Level pairs (point 0, point 1) worth trying, most often best first:
      // on the benchmark matrix and on random two-colour blocks these five
      // come within 1% of the error of all nine pairs.
      constexpr Levels kPairs4[] = {1 | 2 << 2, 0 | 3 << 2, 0 | 1 << 2, 2 | 3 << 2};
      for (const Levels l : kPairs4) refine(p, true, l, search, best);
      refine(p, false, 0 | 1 << 2, search, best);
    } else {
      int order[16];
      principal_order(p, order);
      for (const bool four : {true, false}) {
        Partition parts[2];
        cluster_fit(p, order, four, parts);
        refine(p, four, levels_of_partition(p.n, order, parts[0]), search, best);
        if (parts[1].gain >= kNearTie * parts[0].gain && parts[1].gain > 0.0f)
          refine(p, four, levels_of_partition(p.n, order, parts[1]), search, best);
      }
    }
  }
  pack(p, best, out);
}

double bc1_block_error(const std::uint8_t rgb[16][3], const float weight[16][3],
                       const std::uint8_t block[8]) {
  std::uint8_t dec[16][3];
  decode_bc1_block(block, dec);
  double e = 0.0;
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(dec[i][c]) - static_cast<double>(rgb[i][c]);
      e += (weight ? static_cast<double>(weight[i][c]) : 1.0) * d * d;
    }
  return e;
}

const char* bc1_encoder_name(Bc1Encoder encoder) {
  switch (encoder) {
    case Bc1Encoder::kWeighted:
      return "weighted";
    case Bc1Encoder::kSquishClusterFit:
      return "squish-cluster";
    case Bc1Encoder::kSquishClusterFitMasked:
      return "squish-cluster-masked";
    case Bc1Encoder::kSquishIterativeClusterFit:
      return "squish-iterative";
    case Bc1Encoder::kSquishRangeFit:
      return "squish-range";
    case Bc1Encoder::kStbHighQuality:
      return "stb-hq";
  }
  return "unknown";
}

Bc1Encoder bc1_encoder_from_name(const char* name) {
  std::string valid;
  for (const Bc1Encoder e : kAllBc1Encoders) {
    if (std::strcmp(name, bc1_encoder_name(e)) == 0) return e;
    valid += valid.empty() ? "" : ", ";
    valid += bc1_encoder_name(e);
  }
  throw Error("BC1 encoder", std::string("unknown name '") + name + "' (valid: " + valid + ")");
}

void encode_bc1_block(Bc1Encoder encoder, const std::uint8_t rgb[16][3], const float weight[16][3],
                      std::uint8_t out[8]) {
  if (encoder == Bc1Encoder::kWeighted) {
    if (weight) {
      encode_bc1_block_weighted(rgb, weight, out);
    } else {
      float ones[16][3];
      std::fill(&ones[0][0], &ones[0][0] + 48, 1.0f);
      encode_bc1_block_weighted(rgb, ones, out);
    }
    return;
  }
  // Baselines see the block as an opaque RGBA image (alpha 255, so libsquish
  // never switches texels to transparent black on its own).
  std::uint8_t rgba[16 * 4];
  for (int i = 0; i < 16; ++i) {
    for (int c = 0; c < 3; ++c) rgba[4 * i + c] = rgb[i][c];
    rgba[4 * i + 3] = 255;
  }
  switch (encoder) {
    case Bc1Encoder::kSquishClusterFit:
      squish::Compress(rgba, out, squish::kDxt1 | squish::kColourClusterFit);
      return;
    case Bc1Encoder::kSquishClusterFitMasked: {
      int mask = 0;
      for (int i = 0; i < 16; ++i)
        if (!weight || sanitise(weight[i][0]) > 0.0f || sanitise(weight[i][1]) > 0.0f ||
            sanitise(weight[i][2]) > 0.0f)
          mask |= 1 << i;
      if (mask == 0) {
        const std::uint8_t zero[16] = {};
        write_block(0, 0, zero, out);
        return;
      }
      squish::CompressMasked(rgba, mask, out, squish::kDxt1 | squish::kColourClusterFit);
      return;
    }
    case Bc1Encoder::kSquishIterativeClusterFit:
      squish::Compress(rgba, out, squish::kDxt1 | squish::kColourIterativeClusterFit);
      return;
    case Bc1Encoder::kSquishRangeFit:
      squish::Compress(rgba, out, squish::kDxt1 | squish::kColourRangeFit);
      return;
    case Bc1Encoder::kStbHighQuality:
      stb_compress_dxt_block(out, rgba, 0, STB_DXT_HIGHQUAL);
      return;
    case Bc1Encoder::kWeighted:
      break;
  }
}

}  // namespace bounce
