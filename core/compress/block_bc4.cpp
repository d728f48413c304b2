#include "compress/block_bc4.h"

#include <squish.h>

#include <algorithm>
#include <cmath>
#include <cstring>  // stb_dxt.h calls memcpy without including <string.h>
#include <limits>
#include <string>

#include "base/error.h"

// Declarations only: block_bc1.cpp holds the implementation.
#include <stb/stb_dxt.h>

namespace bounce {

namespace {

// The encoder. One channel with 8-bit endpoints makes the search small, so
// it is direct: for each mode (eight levels; six levels plus exact 0 and
// 255, which fit zeros and holes), start from the endpoints at the range of
// the weighted values (error at most half a level step), then alternate
// "best level per value" and "least-squares endpoints for these levels,
// rounded by an exact search of neighbouring codes with the decoder's
// integer palette" while the weighted error falls. Both modes are scored
// exactly and the better kept.

// Decoded value of line level l (0 = endpoint a, divisions = endpoint b) in
// the mode with `divisions` steps (7: eight levels, 5: six levels); levels
// 6 and 7 of the six-level mode are the constants 0 and 255. The integer
// expression is symmetric under swapping a and b together with l -> divisions
// - l, so a level keeps its value whichever endpoint is stored first.
inline void palette(int divisions, int a, int b, int pal[8]) {
  for (int l = 0; l <= divisions; ++l) pal[l] = ((divisions - l) * a + l * b) / divisions;
  if (divisions == 5) {
    pal[6] = 0;
    pal[7] = 255;
  }
}

struct Points {
  int n = 0;
  float t[16];
  float w[16];  // summed weights, scaled so the largest is 1
  std::int8_t of_texel[16]{};
};

inline float sanitise(float w) {
  if (!(w > 0.0f)) return 0.0f;
  return std::min(w, std::numeric_limits<float>::max());
}

bool gather(const std::uint8_t value[16], const float weight[16], Points& p) {
  float wmax = 0.0f;
  for (int i = 0; i < 16; ++i) wmax = std::max(wmax, sanitise(weight[i]));
  if (!(wmax > 0.0f)) return false;
  const float scale = 1.0f / wmax;
  p.n = 0;
  for (int i = 0; i < 16; ++i) {
    const float w = sanitise(weight[i]) * scale;
    if (!(w > 0.0f)) {
      p.of_texel[i] = -1;
      continue;
    }
    int m = 0;
    while (m < p.n && p.t[m] != static_cast<float>(value[i])) ++m;
    if (m == p.n) {
      p.t[m] = value[i];
      p.w[m] = 0.0f;
      ++p.n;
    }
    p.w[m] += w;
    p.of_texel[i] = static_cast<std::int8_t>(m);
  }
  return true;
}

struct Candidate {
  int divisions = 7;
  int a = 0, b = 0;
  std::uint8_t level[16]{};
  float err = std::numeric_limits<float>::infinity();
};

float assign_levels(const Points& p, int divisions, int a, int b, std::uint8_t level[16]) {
  int ip[8];
  palette(divisions, a, b, ip);
  float total = 0.0f;
  for (int m = 0; m < p.n; ++m) {
    float best = std::numeric_limits<float>::infinity();
    int best_l = 0;
    for (int l = 0; l < 8; ++l) {  // six line levels + 0 and 255, or eight
      const float d = static_cast<float>(ip[l]) - p.t[m];
      if (d * d < best) {
        best = d * d;
        best_l = l;
      }
    }
    level[m] = static_cast<std::uint8_t>(best_l);
    total += p.w[m] * best;
  }
  return total;
}

// Best integer endpoints for fixed levels: least squares on the line levels,
// then an exact search (decoder's integer palette, per-level weight sums)
// over a around its optimum and, for each a, b around its conditional optimum.
void fit_endpoints(const Points& p, int divisions, const std::uint8_t level[16], int& a_out,
                   int& b_out) {
  float wl[8] = {}, xl[8] = {}, ql[8] = {};
  for (int m = 0; m < p.n; ++m) {
    wl[level[m]] += p.w[m];
    xl[level[m]] += p.w[m] * p.t[m];
    ql[level[m]] += p.w[m] * p.t[m] * p.t[m];
  }
  float aa = 0.0f, bb = 0.0f, ab = 0.0f, da = 0.0f, db = 0.0f, wsum = 0.0f, xsum = 0.0f;
  const auto d = static_cast<float>(divisions);
  for (int l = 0; l <= divisions; ++l) {
    const float alpha = (d - static_cast<float>(l)) / d, beta = static_cast<float>(l) / d;
    aa += wl[l] * alpha * alpha;
    bb += wl[l] * beta * beta;
    ab += wl[l] * alpha * beta;
    da += xl[l] * alpha;
    db += xl[l] * beta;
    wsum += wl[l];
    xsum += xl[l];
  }
  if (!(wsum > 0.0f)) return;  // every point on 0 or 255: endpoints do not matter
  float a, b;
  const float det = aa * bb - ab * ab;
  if (det > 1e-5f * aa * bb && aa > 0.0f && bb > 0.0f) {
    a = (bb * da - ab * db) / det;
    b = (aa * db - ab * da) / det;
  } else {
    a = b = xsum / wsum;
  }
  a = std::clamp(a, 0.0f, 255.0f);
  auto error_of = [&](int ea, int eb) {
    int ip[8];
    palette(divisions, ea, eb, ip);
    float e = 0.0f;
    for (int l = 0; l < 8; ++l) {
      const auto v = static_cast<float>(ip[l]);
      e += (wl[l] * v - 2.0f * xl[l]) * v + ql[l];
    }
    return e;
  };
  float best = std::numeric_limits<float>::infinity();
  const int a0 = static_cast<int>(a);
  for (int qa = std::max(0, a0 - 1); qa <= std::min(255, a0 + 2); ++qa) {
    const float bstar =
        bb > 0.0f ? std::clamp((db - ab * static_cast<float>(qa)) / bb, 0.0f, 255.0f) : b;
    const int b0 = static_cast<int>(bstar);
    for (int qb = b0; qb <= std::min(255, b0 + 1); ++qb) {
      const float e = error_of(qa, qb);
      if (e < best) {
        best = e;
        a_out = qa;
        b_out = qb;
      }
    }
  }
}

constexpr int kIterations = 4;

void search_mode(const Points& p, int divisions, Candidate& best) {
  // Start from the range of the values (for six levels, of those that the
  // constants 0 and 255 do not already represent exactly).
  float lo = 256.0f, hi = -1.0f;
  for (int m = 0; m < p.n; ++m) {
    if (divisions == 5 && (p.t[m] == 0.0f || p.t[m] == 255.0f)) continue;
    lo = std::min(lo, p.t[m]);
    hi = std::max(hi, p.t[m]);
  }
  if (hi < lo) lo = hi = 0.0f;
  Candidate cand;
  cand.divisions = divisions;
  cand.a = static_cast<int>(lo);
  cand.b = static_cast<int>(hi);
  Candidate local;
  for (int it = 0; it < kIterations; ++it) {
    cand.err = assign_levels(p, divisions, cand.a, cand.b, cand.level);
    if (!(cand.err < local.err)) break;
    local = cand;
    if (cand.err <= 0.0f) break;
    fit_endpoints(p, divisions, cand.level, cand.a, cand.b);
  }
  if (local.err < best.err) best = local;
}

void write_block(int a0, int a1, const std::uint8_t index[16], std::uint8_t out[8]) {
  out[0] = static_cast<std::uint8_t>(a0);
  out[1] = static_cast<std::uint8_t>(a1);
  for (int half = 0; half < 2; ++half) {
    std::uint32_t bits = 0;
    for (int j = 0; j < 8; ++j) bits |= static_cast<std::uint32_t>(index[8 * half + j]) << (3 * j);
    for (int k = 0; k < 3; ++k) out[2 + 3 * half + k] = static_cast<std::uint8_t>(bits >> (8 * k));
  }
}

}  // namespace

void decode_bc4_block(const std::uint8_t* block, std::uint8_t value[16]) {
  const int a0 = block[0], a1 = block[1];
  int codes[8];
  codes[0] = a0;
  codes[1] = a1;
  if (a0 <= a1) {
    for (int i = 1; i < 5; ++i) codes[1 + i] = ((5 - i) * a0 + i * a1) / 5;
    codes[6] = 0;
    codes[7] = 255;
  } else {
    for (int i = 1; i < 7; ++i) codes[1 + i] = ((7 - i) * a0 + i * a1) / 7;
  }
  for (int half = 0; half < 2; ++half) {
    const std::uint32_t bits = static_cast<std::uint32_t>(block[2 + 3 * half]) |
                               static_cast<std::uint32_t>(block[3 + 3 * half]) << 8 |
                               static_cast<std::uint32_t>(block[4 + 3 * half]) << 16;
    for (int j = 0; j < 8; ++j)
      value[8 * half + j] = static_cast<std::uint8_t>(codes[(bits >> (3 * j)) & 7]);
  }
}

void encode_bc4_block_weighted(const std::uint8_t value[16], const float weight[16],
                               std::uint8_t out[8]) {
  Points p;
  const std::uint8_t zero[16] = {};
  if (!gather(value, weight, p)) {
    write_block(0, 0, zero, out);
    return;
  }
  Candidate best;
  search_mode(p, 7, best);
  if (best.err > 0.0f) search_mode(p, 5, best);
  // Store the endpoints in the order the mode needs; level -> index.
  int a0 = best.a, a1 = best.b;
  std::uint8_t map[8];
  if (best.divisions == 7) {
    if (a0 == a1) {
      std::fill(map, map + 8, std::uint8_t{0});  // decodes in six-level mode: all a0
    } else {
      const bool swap = a0 < a1;
      if (swap) std::swap(a0, a1);
      for (int l = 0; l < 8; ++l) {
        const int k = swap ? 7 - l : l;
        map[l] = static_cast<std::uint8_t>(k == 0 ? 0 : k == 7 ? 1 : k + 1);
      }
    }
  } else {
    const bool swap = a0 > a1;
    if (swap) std::swap(a0, a1);
    for (int l = 0; l < 6; ++l) {
      const int k = swap ? 5 - l : l;
      map[l] = static_cast<std::uint8_t>(k == 0 ? 0 : k == 5 ? 1 : k + 1);
    }
    map[6] = 6;
    map[7] = 7;
  }
  std::uint8_t index[16];
  for (int i = 0; i < 16; ++i) index[i] = p.of_texel[i] < 0 ? 0 : map[best.level[p.of_texel[i]]];
  write_block(a0, a1, index, out);
}

double bc4_block_error(const std::uint8_t value[16], const float weight[16],
                       const std::uint8_t block[8]) {
  std::uint8_t dec[16];
  decode_bc4_block(block, dec);
  double e = 0.0;
  for (int i = 0; i < 16; ++i) {
    const double d = static_cast<double>(dec[i]) - static_cast<double>(value[i]);
    e += (weight ? static_cast<double>(weight[i]) : 1.0) * d * d;
  }
  return e;
}

const char* bc4_encoder_name(Bc4Encoder encoder) {
  switch (encoder) {
    case Bc4Encoder::kWeighted:
      return "weighted";
    case Bc4Encoder::kSquish:
      return "squish";
    case Bc4Encoder::kStb:
      return "stb";
  }
  return "unknown";
}

Bc4Encoder bc4_encoder_from_name(const char* name) {
  std::string valid;
  for (const Bc4Encoder e : kAllBc4Encoders) {
    if (std::strcmp(name, bc4_encoder_name(e)) == 0) return e;
    valid += valid.empty() ? "" : ", ";
    valid += bc4_encoder_name(e);
  }
  throw Error("BC4 encoder", std::string("unknown name '") + name + "' (valid: " + valid + ")");
}

void encode_bc4_block(Bc4Encoder encoder, const std::uint8_t value[16], const float weight[16],
                      std::uint8_t out[8]) {
  switch (encoder) {
    case Bc4Encoder::kWeighted:
      if (weight) {
        encode_bc4_block_weighted(value, weight, out);
      } else {
        float ones[16];
        std::fill(ones, ones + 16, 1.0f);
        encode_bc4_block_weighted(value, ones, out);
      }
      return;
    case Bc4Encoder::kSquish: {
      // libsquish's BC4 path compresses the red channel.
      std::uint8_t rgba[16 * 4] = {};
      for (int i = 0; i < 16; ++i) {
        rgba[4 * i] = value[i];
        rgba[4 * i + 3] = 255;
      }
      squish::Compress(rgba, out, squish::kBc4);
      return;
    }
    case Bc4Encoder::kStb:
      stb_compress_bc4_block(out, value);
      return;
  }
}

}  // namespace bounce
