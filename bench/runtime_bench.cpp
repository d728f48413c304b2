#include "runtime_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <random>

#include "base/error.h"
#include "runtime/compressed_transport.h"
#include "runtime/compressed_transport_cl.h"
#include "runtime/dense_transport.h"
#include "runtime/gather_row_loops.h"
#include "transport/text_format.h"

namespace bounce {

namespace {

using Clock = std::chrono::steady_clock;
using Product = std::function<void(const std::vector<glm::vec3>&, std::vector<glm::vec3>&)>;

void time_product(const Product& product, const std::vector<glm::vec3>& b, int repeats,
                  std::vector<glm::vec3>& out, RuntimeBenchEntry& e) {
  product(b, out);  // warm-up: first touch, caches, the device's first launch
  std::vector<double> ms;
  for (int i = 0; i < repeats; ++i) {
    const auto start = Clock::now();
    product(b, out);
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  std::sort(ms.begin(), ms.end());
  e.best_ms = ms.front();
  e.median_ms = ms[ms.size() / 2];
  e.gb_per_s = e.best_ms > 0.0 ? static_cast<double>(e.bytes) / (e.best_ms * 1e6) : 0.0;
}

double max_rel_diff(const std::vector<glm::vec3>& y, const std::vector<glm::vec3>& reference) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t p = 0; p < reference.size(); ++p)
    for (int k = 0; k < 3; ++k) {
      diff = std::max(diff, std::abs(static_cast<double>(y[p][k]) - reference[p][k]));
      scale = std::max(scale, std::abs(static_cast<double>(reference[p][k])));
    }
  return scale > 0.0 ? diff / scale : diff;
}

// The gather's rows summed one by one in double precision: the reference of
// its rel diff column (float rounding of the sums is all that may differ).
std::vector<glm::vec3> gather_in_double(const FinalGather& g, const std::vector<glm::vec3>& b,
                                        const std::vector<glm::vec3>& sample_light,
                                        const std::vector<glm::vec3>& near_light) {
  std::vector<glm::dvec3> light(g.patches + g.clusters + g.samples + g.near.size(),
                                glm::dvec3(0.0));
  for (std::size_t s = 0; s < g.samples; ++s)
    light[g.patches + g.clusters + s] = glm::dvec3(sample_light[s]);
  for (std::size_t k = 0; k < g.near.size(); ++k)
    light[g.patches + g.clusters + g.samples + k] = glm::dvec3(near_light[k]);
  for (std::size_t p = 0; p < g.patches; ++p) {
    light[p] = glm::dvec3(b[p]);
    // A patch with seen weights reads its samples' light so weighted.
    if (p + 1 < g.seen_first.size() && g.seen_first[p] < g.seen_first[p + 1]) {
      light[p] = glm::dvec3(0.0);
      for (std::uint32_t k = g.seen_first[p]; k < g.seen_first[p + 1]; ++k)
        light[p] +=
            static_cast<double>(g.seen_weight[k]) * glm::dvec3(sample_light[g.seen_sample[k]]);
    }
    light[g.patches + g.cluster_of_patch[p]] += static_cast<double>(g.cluster_share[p]) * light[p];
  }
  std::vector<glm::vec3> out(g.points());
  for (std::size_t i = 0; i < out.size(); ++i) {
    glm::dvec3 e(0.0);
    for (std::uint64_t k = g.first[i]; k < g.first[i + 1]; ++k)
      e += static_cast<double>(g.weight[k]) * light[g.source[k]];
    out[i] = glm::vec3(e);
  }
  return out;
}

}  // namespace

double measure_read_bandwidth(std::size_t bytes, int repeats) {
  const std::size_t count = std::max<std::size_t>(bytes / sizeof(float), 1);
  // Not std::vector: it would zero the array on one thread first.
  const std::unique_ptr<float[]> data(new float[count]);
  const auto size = static_cast<std::ptrdiff_t>(count);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < size; ++i) data[static_cast<std::size_t>(i)] = 1.0f;
  // 16 partial sums per thread: a single running sum would be one long
  // chain of dependent adds, bound by the add latency, not by memory.
  constexpr std::ptrdiff_t kLanes = 16;
  const std::ptrdiff_t chunks = size / kLanes;
  double best = 0.0;
  volatile float sink = 0.0f;  // keeps the sums from being optimised away
  for (int r = 0; r < std::max(repeats, 1); ++r) {
    const auto start = Clock::now();
    float sum = 0.0f;
#pragma omp parallel reduction(+ : sum)
    {
      float part[kLanes] = {};
#pragma omp for schedule(static)
      for (std::ptrdiff_t i = 0; i < chunks; ++i)
        for (std::ptrdiff_t l = 0; l < kLanes; ++l)
          part[l] += data[static_cast<std::size_t>(kLanes * i + l)];
      for (float p : part) sum += p;
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    sink = sink + sum;
    const auto bytes_read = static_cast<double>(chunks * kLanes) * sizeof(float);
    if (seconds > 0.0) best = std::max(best, bytes_read / seconds);
  }
  return best * 1e-9;
}

RuntimeBench run_runtime_bench(const CompressedMatrix& m, const std::array<int, 3>& channel_of_rgb,
                               const std::vector<const float*>& dense, int repeats,
                               const ClassicRadiosity* classic, const FinalGather* gather) {
  RuntimeBench bench;
  bench.n = m.n;
  bench.channels = m.channels;
  bench.format = m.format == DdsFormat::kBc4 ? "BC4" : "BC1";
  bench.repeats = std::max(repeats, 1);
  if (!dense.empty() && dense.size() != static_cast<std::size_t>(m.channels))
    throw Error("bench runtime", std::to_string(dense.size()) + " dense matrices for " +
                                     std::to_string(m.channels) + " stored channels");

  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec3> b(m.n);
  for (glm::vec3& v : b) v = glm::vec3(u(rng), u(rng), u(rng));

  // The float32 loop is the reference of the rel diff column: equal to the
  // decompressed matrix's product up to float32 summation order.
  const CompressedTransport cpu(m, channel_of_rgb, BlockLoop::kFloat32);
  bench.corrections = cpu.tables().corrections();
  std::vector<glm::vec3> reference, out;
  cpu.multiply(b, reference);

  RuntimeBenchEntry cl_entry;
  cl_entry.what = "compressed, OpenCL";
  try {
    const ClCompressedTransport gpu(cpu.tables());
    cl_entry.what += " (" + gpu.device_name() + ")";
    cl_entry.bytes = gpu.bytes_per_product();
    time_product([&gpu](const auto& x, auto& y) { gpu.multiply(x, y); }, b, bench.repeats, out,
                 cl_entry);
    cl_entry.max_rel_diff = max_rel_diff(out, reference);
  } catch (const Error& e) {
    cl_entry.available = false;
    cl_entry.error = e.what();
  }
  bench.entries.push_back(cl_entry);

  // The default loop (what `bounce solve` runs: bfloat16 where the CPU has
  // it, its rel diff is its rounding against float32), then the float32 one
  // (`--float32`) when it is a different loop.
  const CompressedTransport fastest(cpu.tables(), BlockLoop::kFastest);
  const bool same_loop = std::string(fastest.block_loop()) == cpu.block_loop();
  for (const CompressedTransport* t : {&fastest, &cpu}) {
    if (t == &cpu && same_loop) break;
    RuntimeBenchEntry e;
    e.what = std::string("compressed, C++ (") + t->block_loop() + ")";
    e.default_loop = t == &fastest;
    e.bytes = t->bytes_per_product();
    time_product([t](const auto& x, auto& y) { t->multiply(x, y); }, b, bench.repeats, out, e);
    e.max_rel_diff = max_rel_diff(out, reference);
    bench.entries.push_back(e);
  }

  if (!dense.empty()) {
    RuntimeBenchEntry dense_entry;
    dense_entry.what = "dense, OpenBLAS sgemv";
    // One sgemv per colour, each streaming its matrix (dense_transport.h).
    dense_entry.bytes = 3 * m.n * m.n * sizeof(float) + m.n * sizeof(glm::vec3);
    const std::size_t n = m.n;
    time_product([&](const auto& x, auto& y) { dense_indirect(dense, n, channel_of_rgb, x, y); }, b,
                 bench.repeats, out, dense_entry);
    dense_entry.max_rel_diff = max_rel_diff(out, reference);
    bench.entries.push_back(dense_entry);
  }
  if (classic) {
    RuntimeBenchEntry e;
    e.what = "classic radiosity, K = " + std::to_string(classic->bounces()) + " sgemv iterations";
    e.bytes = classic->bytes_per_update() + m.n * sizeof(glm::vec3);
    time_product([classic](const auto& x, auto& y) { classic->multiply(x, y); }, b, bench.repeats,
                 out, e);
    e.max_rel_diff = max_rel_diff(out, reference);
    bench.entries.push_back(e);
  }
  bench.gather.what = "final gather to the vertices";
  bench.gather.available = gather != nullptr;
  if (gather) {
    if (gather->patches != m.n)
      throw Error("bench runtime", "the final gather is for " + std::to_string(gather->patches) +
                                       " patches, the matrix for " + std::to_string(m.n));
    bench.gather_points = gather->points();
    bench.gather_entries = gather->weight.size();
    // Per frame it reads the rows (offset, and a compact entry or a
    // source and a weight), the patches' and clusters' light (padded to 16
    // bytes a source), and writes a colour per vertex.
    const std::size_t entry_bytes = gather->compact.size() == gather->source.size()
                                        ? sizeof(std::uint32_t)
                                        : sizeof(std::uint32_t) + sizeof(float);
    bench.gather_compact = entry_bytes == sizeof(std::uint32_t);
    bench.gather.bytes = gather->first.size() * sizeof(std::uint64_t) +
                         bench.gather_entries * entry_bytes +
                         (gather->patches + gather->clusters) * 4 * sizeof(float) +
                         bench.gather_points * sizeof(glm::vec3);
    // Sample and near sources read a light of their own each frame (the
    // near sources' direct light, a shadow ray each, is not part of this
    // product: bounce solve --json times it as final_gather_near_sources).
    std::vector<glm::vec3> sample_light(gather->samples), near_light(gather->near.size());
    for (glm::vec3& v : sample_light) v = glm::vec3(u(rng), u(rng), u(rng));
    for (glm::vec3& v : near_light) v = glm::vec3(u(rng), u(rng), u(rng));
    bench.gather.bytes += (gather->samples + gather->near.size()) * 4 * sizeof(float);
    time_product(
        [gather, &sample_light, &near_light](const auto& x, auto& y) {
          gather->irradiance(x, sample_light, near_light, y);
        },
        b, bench.repeats, out, bench.gather);
    const std::vector<glm::vec3> in_double = gather_in_double(*gather, b, sample_light, near_light);
    bench.gather.max_rel_diff = max_rel_diff(out, in_double);
    bench.gather.what += " (" + (bench.gather_compact ? gather->compact_loop : "float rows") + ")";
    bench.gather.default_loop = true;
    if (bench.gather_compact) {
      // Every loop this CPU has, on a copy of the rows naming it.
      FinalGather each = *gather;
      for (const gather_loops::CompactLoop& loop : gather_loops::compact_loops()) {
        each.compact_loop = loop.name;
        RuntimeBenchEntry e = bench.gather;
        e.what = "final gather, " + loop.name + " loop";
        e.default_loop = loop.name == gather->compact_loop;
        time_product(
            [&each, &sample_light, &near_light](const auto& x, auto& y) {
              each.irradiance(x, sample_light, near_light, y);
            },
            b, bench.repeats, out, e);
        e.max_rel_diff = max_rel_diff(out, in_double);
        bench.gather_loops.push_back(e);
      }
    }
  }
  bench.stream_gb_per_s = measure_read_bandwidth();
  return bench;
}

std::string runtime_bench_table(const RuntimeBench& bench) {
  double dense_ms = 0.0;
  for (const RuntimeBenchEntry& e : bench.entries)
    if (e.available && e.what.rfind("dense", 0) == 0) dense_ms = e.best_ms;
  std::size_t width = 4;
  for (const RuntimeBenchEntry& e : bench.entries) width = std::max(width, e.what.size());
  const int w = static_cast<int>(width);
  std::string s = text_format(
      "runtime product, n = %zu, %d stored channel%s (%s), %zu kept positions, best / median of "
      "%d\n",
      bench.n, bench.channels, bench.channels == 1 ? "" : "s", bench.format.c_str(),
      bench.corrections, bench.repeats);
  s += text_format("  %-*s %10s %10s %10s %8s %7s %9s %9s\n", w, "path", "best ms", "median ms",
                   "MiB read", "GB/s", "of mem", "vs dense", "rel diff");
  for (const RuntimeBenchEntry& e : bench.entries) {
    if (!e.available) {
      s += text_format("  %-*s unavailable: %s\n", w, e.what.c_str(), e.error.c_str());
      continue;
    }
    const double mib = static_cast<double>(e.bytes) / (1024.0 * 1024.0);
    const double of_memory = bench.stream_gb_per_s > 0.0 ? e.gb_per_s / bench.stream_gb_per_s : 0.0;
    s += text_format("  %-*s %10.3f %10.3f %10.1f %8.1f %6.0f%% ", w, e.what.c_str(), e.best_ms,
                     e.median_ms, mib, e.gb_per_s, 100.0 * of_memory);
    s += dense_ms > 0.0 ? text_format("%8.2fx", dense_ms / e.best_ms) : std::string("        -");
    s += text_format(" %9.2e\n", e.max_rel_diff);
  }
  s += text_format("  read bandwidth of this machine (sum over 512 MiB, best of 5): %.1f GB/s\n",
                   bench.stream_gb_per_s);
  if (bench.gather.available) {
    const RuntimeBenchEntry& g = bench.gather;
    const double of_memory = bench.stream_gb_per_s > 0.0 ? g.gb_per_s / bench.stream_gb_per_s : 0.0;
    s += text_format("final gather, %zu vertices, %zu entries (%.1f per vertex, %s)\n",
                     bench.gather_points, bench.gather_entries,
                     bench.gather_points ? static_cast<double>(bench.gather_entries) /
                                               static_cast<double>(bench.gather_points)
                                         : 0.0,
                     bench.gather_compact ? "4 bytes each: source and ray count"
                                          : "8 bytes each: source and float weight");
    s += text_format("  %-*s %10.3f %10.3f %10.1f %8.1f %6.0f%%         - %9.2e\n", w,
                     g.what.c_str(), g.best_ms, g.median_ms,
                     static_cast<double>(g.bytes) / (1024.0 * 1024.0), g.gb_per_s,
                     100.0 * of_memory, g.max_rel_diff);
    for (const RuntimeBenchEntry& l : bench.gather_loops)
      s += text_format(
          "  %-*s %10.3f %10.3f %10.1f %8.1f %6.0f%%         - %9.2e%s\n", w, l.what.c_str(),
          l.best_ms, l.median_ms, static_cast<double>(l.bytes) / (1024.0 * 1024.0), l.gb_per_s,
          bench.stream_gb_per_s > 0.0 ? 100.0 * l.gb_per_s / bench.stream_gb_per_s : 0.0,
          l.max_rel_diff, l.default_loop ? "  (the loop the product chose)" : "");
  }
  // What the default C++ loop is to reach: >= 8x dense sgemv, and within 2x
  // of the time its bytes take at the measured bandwidth.
  for (const RuntimeBenchEntry& e : bench.entries) {
    if (!e.available || !e.default_loop || e.best_ms <= 0.0) continue;
    s += text_format("  %s, the default loop: %.3f ms", e.what.c_str(), e.best_ms);
    if (dense_ms > 0.0)
      s += text_format(", %.2fx dense sgemv (target >= 8x)", dense_ms / e.best_ms);
    if (bench.stream_gb_per_s > 0.0) {
      const double bound_ms = static_cast<double>(e.bytes) / (bench.stream_gb_per_s * 1e6);
      s += text_format(
          "; its %.1f MiB take %.3f ms at %.1f GB/s, it takes %.2fx that (target <= 2x)",
          static_cast<double>(e.bytes) / (1024.0 * 1024.0), bound_ms, bench.stream_gb_per_s,
          e.best_ms / bound_ms);
    }
    s += "\n";
    if (bench.gather.available)
      s += text_format(
          "  a light update without its direct light: T b %.3f + final gather %.3f = %.3f ms "
          "(target for the whole update <= 16 ms; `bounce solve` times the direct light)\n",
          e.best_ms, bench.gather.best_ms, e.best_ms + bench.gather.best_ms);
  }
  return s;
}

}  // namespace bounce
