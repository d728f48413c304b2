#include "transport/blas_kernels.h"

#include <cblas.h>
#include <dlfcn.h>
#include <strings.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <ctime>
#include <mutex>
#include <vector>

namespace bounce {

namespace {

// OpenBLAS's kernel sets that predate AVX: its fallbacks for a CPU it does
// not know, or the right choice for an old one (then the CPU has no AVX and
// nothing is tried).
constexpr std::array<const char*, 14> kPreAvxKernels = {
    "Prescott",   "Core2",     "Penryn", "Dunnington", "Nehalem",      "Atom",      "Katmai",
    "Coppermine", "Northwood", "Banias", "Opteron",    "Opteron_SSE3", "Barcelona", "Nano"};

std::string corename() {
  const char* name = openblas_get_corename();
  return name ? name : "";
}

bool same_name(const std::string& a, const char* b) { return strcasecmp(a.c_str(), b) == 0; }

bool pre_avx(const std::string& name) {
  return std::any_of(kPreAvxKernels.begin(), kPreAvxKernels.end(),
                     [&](const char* k) { return same_name(name, k); });
}

// The newest kernel set this CPU's instruction sets run, or null.
const char* kernels_for_this_cpu() {
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl"))
    return "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
  if (__builtin_cpu_supports("avx")) return "Sandybridge";
  return nullptr;
}

// Seconds of CPU the calling thread has used.
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// One thread's sgemm GFLOP/s on n = kProbeSize: the best of five, after one
// untimed run, on OpenBLAS with one thread (it then runs on the calling
// thread) and timed in that thread's CPU time. Wall time on a loaded machine
// swung the choice between two runs of one bake, and the kernels round
// differently; the CPU time a thread spends is what the kernels cost,
// whatever else runs.
double sgemm_gflops() {
  constexpr int n = BlasKernels::kProbeSize;
  std::vector<float> a(std::size_t{n} * n, 0.5f), b(a), c(a.size());
  const int threads = openblas_get_num_threads();
  openblas_set_num_threads(1);
  double best = 1e30;
  for (int run = 0; run < 6; ++run) {
    const double t = thread_cpu_seconds();
    cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, n, n, n, 1.0f, a.data(), n, b.data(), n,
                0.0f, c.data(), n);
    const double s = thread_cpu_seconds() - t;
    if (run > 0 && s > 0.0) best = std::min(best, s);
  }
  openblas_set_num_threads(threads);
  return 2.0 * n * n * n / best * 1e-9;
}

using InitFunction = void (*)();

// Re-initialises OpenBLAS's kernel table on `name` (its dynamic build reads
// OPENBLAS_CORETYPE when it initialises). False when this OpenBLAS cannot.
bool switch_kernels(const char* name) {
  const auto quit = reinterpret_cast<InitFunction>(dlsym(RTLD_DEFAULT, "gotoblas_dynamic_quit"));
  const auto init = reinterpret_cast<InitFunction>(dlsym(RTLD_DEFAULT, "gotoblas_dynamic_init"));
  if (!quit || !init) return false;
  const std::unique_lock lock(blas_threads_mutex());
  setenv("OPENBLAS_CORETYPE", name, 1);
  quit();
  init();
  unsetenv("OPENBLAS_CORETYPE");
  return same_name(corename(), name);
}

BlasKernels decide() {
  BlasKernels k;
  k.detected = k.used = corename();
  if (std::getenv("OPENBLAS_CORETYPE")) {
    k.why = "set by OPENBLAS_CORETYPE";
    return k;
  }
  const char* candidate = kernels_for_this_cpu();
  if (!pre_avx(k.detected) || !candidate) {
    k.why = "OpenBLAS's own choice for this CPU";
    return k;
  }
  const double detected_gflops = sgemm_gflops();
  if (!switch_kernels(candidate)) {
    switch_kernels(k.detected.c_str());
    k.why = std::string("OpenBLAS's own choice: this OpenBLAS cannot switch to ") + candidate;
    return k;
  }
  k.candidate = candidate;
  k.detected_gflops = detected_gflops;
  k.candidate_gflops = sgemm_gflops();
  if (k.candidate_gflops > k.detected_gflops) {
    k.used = candidate;
    k.why = "OpenBLAS fell back to " + k.detected + " on a CPU it does not know; " + candidate +
            ", which this CPU's instruction sets run, was faster";
  } else {
    switch_kernels(k.detected.c_str());
    k.why = "OpenBLAS's own choice: " + std::string(candidate) + " was not faster";
  }
  return k;
}

}  // namespace

std::shared_mutex& blas_threads_mutex() {
  static std::shared_mutex m;
  return m;
}

const BlasKernels& choose_blas_kernels() {
  static std::once_flag once;
  static BlasKernels chosen;
  std::call_once(once, [] { chosen = decide(); });
  return chosen;
}

}  // namespace bounce
