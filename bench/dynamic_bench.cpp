#include "dynamic_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <string>

#include "base/error.h"
#include "dynamic/local_transport.h"
#include "dynamic/temporal_radiosity_cl.h"
#include "metrics/image_metrics.h"
#include "runtime/classic_radiosity.h"
#include "runtime/dense_transport.h"
#include "runtime/frame_graph.h"
#include "transport/inverse_transport.h"
#include "transport/spectral_radius.h"

namespace bounce {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double max_abs(const std::vector<float>& a) {
  double m = 0.0;
  for (float x : a) m = std::max(m, std::abs(static_cast<double>(x)));
  return m;
}

double max_diff(const std::vector<float>& a, const std::vector<float>& b) {
  double m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    m = std::max(m, std::abs(static_cast<double>(a[i]) - b[i]));
  return m;
}

// A way to produce the indirect light frame by frame: reset() forgets the
// history, frame(b) computes this frame's indirect light into `out`.
struct FrameMethod {
  std::function<void()> reset;
  std::function<void(const std::vector<glm::vec3>& b, std::vector<glm::vec3>& out)> frame;
};

// Errors after 1, 4, 16, 64 frames on the first light; then the light
// jumps and ghosting lasts until the error is back under `threshold` (1.5x
// this method's own error after 64 frames, or 1e-3 for exact methods);
// then the best time of `repeats` frames. With `full_image` (the full
// product's camera picture of the first light) the pictures at the same
// marks are compared with it, and with a reference the picture after
// in.reference_frames frames of the scene's lights with the path tracer's.
// What every method is compared with: the full product of each light, and
// its pictures.
struct References {
  std::vector<glm::vec3> light, jumped;
  std::vector<std::vector<glm::vec3>> moving;
  const RgbFloatImage* image = nullptr;      // of `light`
  RgbFloatImage jumped_image, moving_image;  // of `jumped`, of the last moving light
};

void measure(DynamicMethodRow& row, const FrameMethod& m, const DynamicBenchInput& in,
             const DynamicBenchSettings& s, const References& refs) {
  const std::vector<glm::vec3>& ref0 = refs.light;
  const std::vector<glm::vec3>& ref1 = refs.jumped;
  const RgbFloatImage* full_image = refs.image;
  std::vector<glm::vec3> out;
  m.reset();
  std::size_t next = 0;
  const int marks[4] = {1, 4, 16, 64};
  for (int f = 1; f <= 64; ++f) {
    m.frame(in.light, out);
    if (f != marks[next]) continue;
    row.error[next] = relative_rms(out, ref0, in.area);
    if (full_image) {
      const ImageErrors e = image_errors(in.render_indirect(out), *full_image, in.image_mask);
      row.images = true;
      row.image_ssim[next] = e.ssim;
      row.image_error[next] = e.relative_rmse;
    }
    ++next;
  }
  if (full_image && !in.scene_light.empty() && in.reference_indirect.width > 0) {
    m.reset();
    for (int f = 0; f < in.reference_frames; ++f) m.frame(in.scene_light, out);
    const RgbFloatImage picture = in.render_indirect(out);
    row.against_reference = true;
    row.reference_error = noise_corrected_relative_rmse(picture, in.reference_indirect,
                                                        in.reference_variance, in.image_mask);
    row.reference_ssim = image_errors(picture, in.reference_indirect, in.image_mask).ssim;
  }
  const double threshold = std::max(1.5 * row.error[3], 1e-3);
  row.ghosting_frames = -1;
  std::vector<glm::vec3> previous;
  for (int f = 0; f < s.ghosting_limit; ++f) {
    m.frame(in.jumped_light, out);
    if (full_image && (f == 0 || f == 3))
      row.jump_ssim[f == 0 ? 0 : 1] =
          image_errors(in.render_indirect(out), refs.jumped_image, in.image_mask).ssim;
    if (f >= 3 && row.ghosting_frames >= 0) break;
    if (row.ghosting_frames >= 0) continue;
    if (relative_rms(out, ref1, in.area) <= threshold) {
      row.ghosting_frames = f;  // frames before the first good one
      continue;
    }
    // A method without history repeats itself: it will never get closer.
    if (out == previous && f >= 3) break;
    previous = out;
  }
  if (!in.moving_light.empty()) {
    m.reset();
    row.moving = true;
    double ms = 0.0, error = 0.0;
    for (std::size_t f = 0; f < in.moving_light.size(); ++f) {
      const auto start = Clock::now();
      m.frame(in.moving_light[f], out);
      ms += ms_since(start);
      error += relative_rms(out, refs.moving[f], in.area);
    }
    const auto frames = static_cast<double>(in.moving_light.size());
    row.moving_ms = ms / frames;
    row.moving_error = error / frames;
    if (full_image)
      row.moving_ssim =
          image_errors(in.render_indirect(out), refs.moving_image, in.image_mask).ssim;
  }
  m.reset();
  m.frame(in.light, out);  // warm-up
  row.ms_per_frame = std::numeric_limits<double>::infinity();
  for (int r = 0; r < s.repeats; ++r) {
    const auto start = Clock::now();
    m.frame(in.light, out);
    row.ms_per_frame = std::min(row.ms_per_frame, ms_since(start));
  }
}

std::size_t matrix_bytes(std::size_t n, std::size_t channels) {
  return channels * n * n * sizeof(float);
}

// What the runtime's compressed product holds: the tables, the block
// records its AVX-512 loops read besides the blocks (10 bytes per block),
// and its stored-order b and y.
std::size_t compressed_product_bytes(const CompressedTransport& ct) {
  const CompressedTransportTables& t = ct.tables();
  const std::string loop = ct.block_loop();
  const std::size_t nb = t.block_rows;
  std::size_t records = 0;
  if (loop == "avx512-bf16") records = (nb + 7) / 8 * nb * sizeof(Bc1BlockGroup);
  if (loop == "avx512") records = (nb + 1) / 2 * nb * sizeof(Bc1BlockPair);
  return t.bytes() + records + t.padded * (3 + 4 + 3) * sizeof(float);
}

std::size_t graph_transient_bytes(std::size_t n, int channels, bool temporal, bool alias) {
  FrameGraph g = dynamic_radiosity_memory_graph(n, channels, temporal);
  g.compile(alias);
  return g.transient_bytes();
}

void run_local_matrix(DynamicBench& out, const DynamicBenchInput& in) {
  const std::size_t n = in.n;
  // The colour of stored channel 0.
  glm::length_t colour = 0;
  while (colour < 3 && in.channel_of_rgb[static_cast<std::size_t>(colour)] != 0) ++colour;
  std::vector<float> rho(n), m(n * n);
  for (std::size_t p = 0; p < n; ++p) rho[p] = in.albedo[p][colour];
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = 0; q < n; ++q) m[p * n + q] = rho[p] * in.form_factors[p * n + q];
  const SpectralRadius radius = estimate_spectral_radius(m.data(), n);
  if (!(radius.upper < 1.0)) throw Error("bench dynamic", "spectral radius of M is not below 1");
  // The exact K = infinity matrix, so the comparison isolates the update
  // (the bake's T may be a truncated series).
  const InverseTransport full = solve_infinite_bounces(m, n, radius.upper);
  const double scale = max_abs(full.t);
  std::vector<bool> all(n, true);
  std::vector<float> column, row;
  for (std::size_t k : {n / 3, (2 * n) / 3}) {
    LocalMatrixRow r;
    r.patch = k;
    LocalTransport local(full.t, n, all);
    auto start = Clock::now();
    local.remove_patch(k);
    r.remove_ms = ms_since(start);
    std::vector<float> reduced = m;
    for (std::size_t i = 0; i < n; ++i) reduced[i * n + k] = reduced[k * n + i] = 0.0f;
    start = Clock::now();
    const InverseTransport ref = solve_infinite_bounces(std::move(reduced), n, radius.upper);
    r.recompute_ms = ms_since(start);
    r.remove_vs_recompute = max_diff(local.matrix(), ref.t) / scale;
    transport_column_and_row(in.form_factors, rho, k, column, row);
    start = Clock::now();
    r.sigma = local.add_patch(k, column, row);
    r.add_ms = ms_since(start);
    r.round_trip = max_diff(local.matrix(), full.t) / scale;
    out.local.push_back(r);
  }
}

}  // namespace

double relative_rms(const std::vector<glm::vec3>& y, const std::vector<glm::vec3>& exact,
                    const std::vector<float>& area) {
  if (y.size() != exact.size() || area.size() != exact.size())
    throw Error("bench dynamic", "vectors of different sizes");
  double num = 0.0, den = 0.0;
  for (std::size_t p = 0; p < y.size(); ++p) {
    const glm::dvec3 d = glm::dvec3(y[p]) - glm::dvec3(exact[p]);
    num += area[p] * glm::dot(d, d);
    den += area[p] * glm::dot(glm::dvec3(exact[p]), glm::dvec3(exact[p]));
  }
  return den > 0.0 ? std::sqrt(num / den) : std::sqrt(num);
}

DynamicBench run_dynamic_bench(const DynamicBenchInput& in, const DynamicBenchSettings& s) {
  const std::size_t n = in.n;
  if (in.transport.empty()) throw Error("bench dynamic", "no transport matrix");
  if (in.light.size() != n || in.jumped_light.size() != n || in.area.size() != n)
    throw Error("bench dynamic", "light or area vectors do not match the patch count");
  if (s.repeats < 1) throw Error("bench dynamic", "--repeats must be at least 1");
  DynamicBench out;
  out.n = n;
  const std::size_t channels = in.transport.size();
  const int ch = static_cast<int>(channels);
  const std::size_t vec = n * sizeof(glm::vec3);

  References refs;
  std::vector<glm::vec3>& ref0 = refs.light;
  dense_indirect(in.transport, n, in.channel_of_rgb, in.light, ref0);
  dense_indirect(in.transport, n, in.channel_of_rgb, in.jumped_light, refs.jumped);
  for (const std::vector<glm::vec3>& b : in.moving_light) {
    if (b.size() != n)
      throw Error("bench dynamic", "a moving light does not match the patch count");
    refs.moving.emplace_back();
    dense_indirect(in.transport, n, in.channel_of_rgb, b, refs.moving.back());
  }
  if (!in.scene_light.empty() && in.scene_light.size() != n)
    throw Error("bench dynamic", "the scene's light vector does not match the patch count");
  RgbFloatImage full_picture;
  const RgbFloatImage* full_image = nullptr;
  if (in.render_indirect) {
    full_picture = in.render_indirect(ref0);
    full_image = &full_picture;
    refs.image = full_image;
    refs.jumped_image = in.render_indirect(refs.jumped);
    if (!refs.moving.empty()) refs.moving_image = in.render_indirect(refs.moving.back());
    out.image_width = full_picture.width;
    out.image_height = full_picture.height;
    if (in.reference_indirect.width > 0) {
      double var = 0.0, sq = 0.0;
      for (std::size_t i = 0; i < in.reference_indirect.pixels.size(); ++i)
        if (in.image_mask.empty() || in.image_mask[i])
          for (glm::length_t c = 0; c < 3; ++c) {
            var += in.reference_variance.pixels[i][c];
            sq += static_cast<double>(in.reference_indirect.pixels[i][c]) *
                  in.reference_indirect.pixels[i][c];
          }
      out.reference_noise = sq > 0.0 ? std::sqrt(var / sq) : 0.0;
    }
  }

  {
    DynamicMethodRow row;
    row.method = "full multi-bounce product (dense sgemv)";
    row.note = "the reference";
    measure(row,
            {[] {},
             [&](const std::vector<glm::vec3>& b, std::vector<glm::vec3>& y) {
               dense_indirect(in.transport, n, in.channel_of_rgb, b, y);
             }},
            in, s, refs);
    row.persistent_bytes = matrix_bytes(n, channels);
    row.transient_bytes = graph_transient_bytes(n, ch, false, false);
    row.bytes_per_frame = matrix_bytes(n, channels) + 2 * vec;
    out.methods.push_back(row);
  }

  if (in.compressed) {
    const CompressedTransport& ct = *in.compressed;
    if (ct.size() != n) throw Error("bench dynamic", "the compressed matrix's size differs");
    {
      DynamicMethodRow row;
      row.method = "compressed product (C++)";
      row.note = ct.block_loop();
      measure(row,
              {[] {}, [&](const std::vector<glm::vec3>& b,
                          std::vector<glm::vec3>& y) { ct.multiply(b, y); }},
              in, s, refs);
      row.persistent_bytes = compressed_product_bytes(ct);
      row.transient_bytes = graph_transient_bytes(n, ch, false, false);
      row.bytes_per_frame = ct.bytes_per_product();
      out.methods.push_back(row);
    }
    {
      DynamicMethodRow row;
      row.method = "temporal, light importance, compressed T";
      LightTemporalRadiosity light(ct.tables(), s.light_temporal);
      std::vector<glm::vec3> history(n, glm::vec3(0.0f));
      measure(row,
              {[&] { light.reset(); },
               [&](const std::vector<glm::vec3>& b, std::vector<glm::vec3>& y) {
                 light.step(b, history);
                 y = history;
               }},
              in, s, refs);
      char note[160];
      std::snprintf(note, sizeof note, "S = %d of %zu block columns, %zu drawn, %zu kept entries",
                    s.light_temporal.block_columns, ct.tables().block_rows,
                    light.last_block_columns(), light.last_kept_entries());
      row.note = note;
      // What it needs of the tables (blocks, palettes; shared with the
      // runtime's product), its kept entries by column, O(n) buffers, the
      // history.
      row.persistent_bytes = light.table_bytes_read() + light.own_bytes() + vec;
      row.transient_bytes = graph_transient_bytes(n, ch, true, false);
      row.bytes_per_frame = light.last_bytes_read();
      out.methods.push_back(row);
    }
  }

  TemporalRadiosity temporal(in.transport, n, in.channel_of_rgb, s.temporal);
  std::size_t tables = 0;
  for (const AliasTables& t : temporal.tables()) tables += t.bytes();
  {
    DynamicMethodRow row;
    row.method = "temporal radiosity, C++";
    std::vector<glm::vec3> history;
    measure(row,
            {[&] {
               temporal.reset();
               history.assign(n, glm::vec3(0.0f));
             },
             [&](const std::vector<glm::vec3>& b, std::vector<glm::vec3>& y) {
               temporal.step(b, history);
               y = history;
             }},
            in, s, refs);
    row.persistent_bytes = tables + vec;
    row.transient_bytes = graph_transient_bytes(n, ch, true, false);
    row.bytes_per_frame = temporal.bytes_per_frame();
    out.methods.push_back(row);
  }
  {
    DynamicMethodRow row;
    row.method = "temporal radiosity, OpenCL";
    try {
      ClTemporalRadiosity cl(temporal);
      row.note = cl.device_name();
      measure(row,
              {[&] { cl.reset(); },
               [&](const std::vector<glm::vec3>& b, std::vector<glm::vec3>& y) {
                 cl.step(b);
                 cl.read_history(y);
               }},
              in, s, refs);
      row.persistent_bytes = tables + vec;
      row.transient_bytes = graph_transient_bytes(n, ch, true, false);
      row.bytes_per_frame = temporal.bytes_per_frame();
    } catch (const Error& e) {
      row.available = false;
      row.note = e.what();
    }
    out.methods.push_back(row);
  }
  {
    // The frame run through the graph: direct light E (the first-hit light
    // handed in), temporal estimate into B_new, blend into the history,
    // apply (the indirect light handed to the display), transients in one
    // aliased arena.
    DynamicMethodRow row;
    row.method = "temporal + aliasing (frame graph), C++";
    std::vector<glm::vec3> history(n), applied(n);
    const std::vector<glm::vec3>* current_b = &in.light;
    FrameGraph g;
    const auto e = g.add_transient("E", vec);
    const auto b_new = g.add_transient("B_new", vec);
    const auto hist = g.add_imported("history", history.data(), vec);
    const auto output = g.add_imported("applied", applied.data(), vec);
    g.add_pass("direct light", {}, {e}, [&, e](const FrameGraph::Context& c) {
      std::copy(current_b->begin(), current_b->end(), c.get<glm::vec3>(e));
    });
    g.add_pass("temporal estimate", {e}, {b_new}, [&, e, b_new](const FrameGraph::Context& c) {
      temporal.estimate(c.get<glm::vec3>(e), temporal.frame(), c.get<glm::vec3>(b_new));
    });
    g.add_pass("temporal blend", {b_new, hist}, {hist},
               [&, b_new, hist](const FrameGraph::Context& c) {
                 temporal_blend(c.get<glm::vec3>(hist), c.get<glm::vec3>(b_new), n,
                                temporal_blend_weight(s.temporal.history_weight, temporal.frame()));
               });
    g.add_pass("apply", {e, hist}, {output}, [&, hist, output](const FrameGraph::Context& c) {
      std::copy(c.get<glm::vec3>(hist), c.get<glm::vec3>(hist) + n, c.get<glm::vec3>(output));
    });
    g.compile(true);
    measure(row,
            {[&] {
               temporal.reset();
               std::fill(history.begin(), history.end(), glm::vec3(0.0f));
             },
             [&](const std::vector<glm::vec3>& b, std::vector<glm::vec3>& y) {
               current_b = &b;
               g.execute();
               temporal.advance_frame();
               y = applied;
             }},
            in, s, refs);
    row.persistent_bytes = tables + vec;
    row.transient_bytes = graph_transient_bytes(n, ch, true, true);
    row.bytes_per_frame = temporal.bytes_per_frame();
    out.methods.push_back(row);
  }
  {
    DynamicMethodRow row;
    row.method = "classic, K = " + std::to_string(in.classic_bounces) + " iterations on F";
    if (!s.classic) {
      row.available = false;
      row.note = "skipped (--no-classic)";
    } else if (!in.form_factors) {
      row.available = false;
      row.note = "the bake has no F.npy (bake with --dump-matrices)";
    } else {
      ClassicRadiosity classic(std::vector<float>(in.form_factors, in.form_factors + n * n),
                               in.albedo, in.classic_bounces);
      measure(row,
              {[] {}, [&](const std::vector<glm::vec3>& b,
                          std::vector<glm::vec3>& y) { classic.multiply(b, y); }},
              in, s, refs);
      row.persistent_bytes = n * n * sizeof(float) + n * sizeof(glm::vec3);
      row.transient_bytes = 2 * n * sizeof(float) + 2 * vec;  // v, w; E, B
    }
    out.methods.push_back(row);
  }
  if (in.form_factors && s.local_matrix) run_local_matrix(out, in);

  const auto memory = [&](std::string scene, std::size_t patches) {
    out.memory.push_back({std::move(scene), patches,
                          graph_transient_bytes(patches, ch, true, false),
                          graph_transient_bytes(patches, ch, true, true)});
  };
  memory("this bake", n);
  memory("paper's Cornell box with cubes (1736 polygons)", 1736);
  memory("paper's Crytek Sponza (262267 polygons)", 262267);
  memory("paper's Cornell box with dragon (871414 polygons)", 871414);
  return out;
}

std::string dynamic_bench_table(const DynamicBench& b) {
  std::string s;
  char line[512];
  std::snprintf(line, sizeof line, "%-42s %10s %9s %9s %9s %9s %8s %11s %11s %9s\n", "method",
                "ms/frame", "err@1", "err@4", "err@16", "err@64", "ghost", "persist MB",
                "transient MB", "MB read");
  s += line;
  for (const DynamicMethodRow& r : b.methods) {
    if (!r.available) {
      std::snprintf(line, sizeof line, "%-42s unavailable: %s\n", r.method.c_str(), r.note.c_str());
      s += line;
      continue;
    }
    char ghost[32];
    if (r.ghosting_frames < 0)
      std::snprintf(ghost, sizeof ghost, "never");
    else
      std::snprintf(ghost, sizeof ghost, "%d", r.ghosting_frames);
    std::snprintf(
        line, sizeof line, "%-42s %10.3f %9.2e %9.2e %9.2e %9.2e %8s %11.3f %11.4f %9.3f\n",
        r.method.c_str(), r.ms_per_frame, r.error[0], r.error[1], r.error[2], r.error[3], ghost,
        static_cast<double>(r.persistent_bytes) / 1e6, static_cast<double>(r.transient_bytes) / 1e6,
        static_cast<double>(r.bytes_per_frame) / 1e6);
    s += line;
  }
  for (const DynamicMethodRow& r : b.methods)
    if (r.available && r.note.rfind("S = ", 0) == 0) s += "  (" + r.method + ": " + r.note + ")\n";
  if (std::any_of(b.methods.begin(), b.methods.end(),
                  [](const DynamicMethodRow& r) { return r.moving; })) {
    s += "\nmoving light: mean ms per frame along the path, mean patch error against each "
         "frame's full product, last frame's picture SSIM\n";
    for (const DynamicMethodRow& r : b.methods) {
      if (!r.available || !r.moving) continue;
      std::snprintf(line, sizeof line, "%-42s %10.3f %9.2e %8.4f\n", r.method.c_str(), r.moving_ms,
                    r.moving_error, r.moving_ssim);
      s += line;
    }
  }
  if (!b.local.empty()) {
    s += "\nlocal matrix (stored channel 0, against T by LU of the same F):\n";
    std::snprintf(line, sizeof line, "%8s %8s %11s %9s %14s %16s %12s\n", "patch", "sigma",
                  "remove ms", "add ms", "recompute ms", "remove vs LU", "round trip");
    s += line;
    for (const LocalMatrixRow& r : b.local) {
      std::snprintf(line, sizeof line, "%8zu %8.4f %11.2f %9.2f %14.1f %16.2e %12.2e\n", r.patch,
                    r.sigma, r.remove_ms, r.add_ms, r.recompute_ms, r.remove_vs_recompute,
                    r.round_trip);
      s += line;
    }
  }
  if (b.image_width > 0) {
    std::snprintf(line, sizeof line,
                  "\nscene camera's indirect picture (%dx%d) against the full product's: SSIM "
                  "and relative RMSE after f frames%s\n",
                  b.image_width, b.image_height,
                  b.reference_noise > 0.0 ? "; and after 64 frames of the scene's lights "
                                            "against the path-traced reference"
                                          : "");
    s += line;
    std::snprintf(line, sizeof line, "%-42s %7s %7s %7s %7s %9s %9s %9s %9s %7s %7s %9s %8s\n",
                  "method", "SSIM@1", "SSIM@4", "SSIM@16", "SSIM@64", "rel@1", "rel@4", "rel@16",
                  "rel@64", "jump@1", "jump@4", "ref err", "ref SSIM");
    s += line;
    for (const DynamicMethodRow& r : b.methods) {
      if (!r.available || !r.images) continue;
      char reference[64] = "";
      if (r.against_reference)
        std::snprintf(reference, sizeof reference, "%9.3f %8.4f", r.reference_error,
                      r.reference_ssim);
      std::snprintf(line, sizeof line,
                    "%-42s %7.4f %7.4f %7.4f %7.4f %9.2e %9.2e %9.2e %9.2e %7.4f %7.4f %s\n",
                    r.method.c_str(), r.image_ssim[0], r.image_ssim[1], r.image_ssim[2],
                    r.image_ssim[3], r.image_error[0], r.image_error[1], r.image_error[2],
                    r.image_error[3], r.jump_ssim[0], r.jump_ssim[1], reference);
      s += line;
    }
    if (b.reference_noise > 0.0) {
      std::snprintf(line, sizeof line,
                    "  ref err: noise-corrected relative RMSE (the reference's own noise %.3f); "
                    "the full product's is the bake's own error\n",
                    b.reference_noise);
      s += line;
    }
  }
  s += "\ntransient memory per frame (local-matrix update + temporal radiosity), MB:\n";
  for (const TransientMemoryRow& r : b.memory) {
    std::snprintf(line, sizeof line, "  %-52s %8zu patches  %10.4f -> %10.4f\n", r.scene.c_str(),
                  r.patches, static_cast<double>(r.unaliased_bytes) / 1e6,
                  static_cast<double>(r.aliased_bytes) / 1e6);
    s += line;
  }
  return s;
}

std::unique_ptr<CompressedTransport> compressed_product(
    const std::optional<CompressedMatrix>& matrix, const std::array<int, 3>& channel_of_rgb) {
  if (!matrix) return nullptr;
  return std::make_unique<CompressedTransport>(*matrix, channel_of_rgb);
}

}  // namespace bounce
