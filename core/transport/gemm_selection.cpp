#include "transport/gemm_selection.h"

#include <algorithm>
#include <map>
#include <mutex>
#include <string>

#include "transport/clblast_gemm.h"
#include "transport/gemm_timing.h"
#include "transport/openblas_gemm.h"
#include "transport/text_format.h"

namespace bounce {

namespace {

constexpr std::size_t kProbeSize = 512;

// CLBlast first, OpenBLAS from the first CLBlast failure on. A failed product
// leaves C untouched (it is read back only on success), so it is simply redone.
class FallbackGemm final : public GemmBackend {
 public:
  FallbackGemm(std::unique_ptr<GemmBackend> primary, Diagnostics& diagnostics)
      : primary_(std::move(primary)), diagnostics_(diagnostics) {}
  std::string name() const override {
    return failed_ ? fallback_.name() + " (after " + primary_->name() + " failed)"
                   : primary_->name();
  }
  void multiply(std::size_t n, const float* a, const float* b, float beta, float* c) override {
    if (!failed_) {
      try {
        primary_->multiply(n, a, b, beta, c);
        return;
      } catch (const OpenClError& e) {
        failed_ = true;
        diagnostics_.warn("transport.backend", std::string(e.what()) +
                                                   "; continuing on OpenBLAS for the rest of "
                                                   "the transport stage");
      }
    }
    fallback_.multiply(n, a, b, beta, c);
  }

 private:
  std::unique_ptr<GemmBackend> primary_;
  OpenBlasGemm fallback_;
  Diagnostics& diagnostics_;
  bool failed_ = false;
};

struct Probe {
  double openblas_seconds = 0.0;
  double clblast_seconds = 0.0;
};

// Opens CLBlast, or says why not (warning + decision) and returns null.
std::unique_ptr<ClblastGemm> open_clblast(Diagnostics& diagnostics,
                                          std::vector<TransportDecision>& decisions) {
  try {
    return std::make_unique<ClblastGemm>();
  } catch (const Error& e) {
    diagnostics.warn("transport.backend",
                     std::string("CLBlast unavailable, using OpenBLAS: ") + e.what());
    decisions.push_back({"GEMM backend: OpenBLAS", std::string("CLBlast unavailable: ") + e.what()});
    return nullptr;
  }
}

}  // namespace

GemmSelection select_gemm_backend(const TransportSettings& settings, std::size_t n,
                                  std::size_t gemms, Diagnostics& diagnostics,
                                  std::vector<TransportDecision>& decisions) {
  using Backend = TransportSettings::Backend;
  const Backend requested = settings.backend;
  GemmSelection out;
  if (requested == Backend::OpenBLAS) {
    decisions.push_back({"GEMM backend: OpenBLAS", "requested"});
    out.backend = std::make_unique<OpenBlasGemm>();
    return out;
  }
  const std::size_t size = std::max<std::size_t>(std::min(n, kProbeSize), 1);
  if (requested == Backend::Auto) {
    // OpenBLAS's time for the whole job, scaled from one product (n^3).
    OpenBlasGemm openblas;
    const double one = time_gemm(openblas, size, 1).best_seconds;
    const double scale = static_cast<double>(n) / static_cast<double>(size);
    const double predicted = one * scale * scale * scale * static_cast<double>(gemms);
    if (predicted < settings.auto_probe_min_seconds) {
      decisions.push_back(
          {"GEMM backend: OpenBLAS",
           text_format("Auto: the %zu products are predicted to take %.3g s on OpenBLAS (from "
                       "one %zux%zu product), less than the %.3g s below which probing CLBlast "
                       "(kernel compilation on first use) does not pay; CLBlast not probed",
                       gemms, predicted, size, size, settings.auto_probe_min_seconds)});
      out.backend = std::make_unique<OpenBlasGemm>();
      return out;
    }
  }
  std::unique_ptr<ClblastGemm> clblast = open_clblast(diagnostics, decisions);
  if (!clblast) {
    out.backend = std::make_unique<OpenBlasGemm>();
    return out;
  }
  if (requested == Backend::CLBlast) {
    decisions.push_back({"GEMM backend: " + clblast->name(), "requested"});
    out.backend = std::make_unique<FallbackGemm>(std::move(clblast), diagnostics);
    return out;
  }

  static std::mutex mutex;
  static std::map<std::size_t, Probe> probes;  // by probe size
  std::lock_guard lock(mutex);
  auto it = probes.find(size);
  const bool measured_now = it == probes.end();
  if (measured_now) {
    Probe p;
    OpenBlasGemm openblas;
    p.openblas_seconds = time_gemm(openblas, size, 3).best_seconds;
    try {
      p.clblast_seconds = time_gemm(*clblast, size, 3).best_seconds;
    } catch (const OpenClError& e) {
      diagnostics.warn("transport.backend",
                       std::string("CLBlast failed its timing probe, using OpenBLAS: ") + e.what());
      decisions.push_back(
          {"GEMM backend: OpenBLAS", std::string("CLBlast failed its timing probe: ") + e.what()});
      out.backend = std::make_unique<OpenBlasGemm>();
      return out;
    }
    it = probes.emplace(size, p).first;
  }
  const Probe& p = it->second;
  out.probe_n = size;
  out.openblas_seconds = p.openblas_seconds;
  out.clblast_seconds = p.clblast_seconds;
  const std::string why = text_format(
      "Auto: one %zux%zu product, best of 3%s: OpenBLAS %.3g ms, %s %.3g ms (%.2fx OpenBLAS)", size,
      size, measured_now ? "" : " (measured earlier in this process)", p.openblas_seconds * 1e3,
      clblast->name().c_str(), p.clblast_seconds * 1e3,
      p.openblas_seconds > 0.0 ? p.clblast_seconds / p.openblas_seconds : 0.0);
  if (p.clblast_seconds < p.openblas_seconds) {
    decisions.push_back({"GEMM backend: " + clblast->name(), why});
    out.backend = std::make_unique<FallbackGemm>(std::move(clblast), diagnostics);
  } else {
    decisions.push_back({"GEMM backend: OpenBLAS", why});
    out.backend = std::make_unique<OpenBlasGemm>();
  }
  return out;
}

}  // namespace bounce
