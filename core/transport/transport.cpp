#include "transport/transport.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "base/error.h"
#include "transport/blas_kernels.h"
#include "transport/bounce_series.h"
#include "transport/flush_subnormals.h"
#include "transport/gemm_selection.h"
#include "transport/spectral_radius.h"
#include "transport/text_format.h"

namespace bounce {

namespace {

// Albedo channels closer than this everywhere are the same channel: albedo
// comes from 8-bit textures or decimal MTL values, so real differences are
// far larger, and float rounding of equal inputs far smaller.
constexpr float kSameAlbedo = 1e-6f;

// Progress units: one product is 12; an LU is 4 for the factorisation (a
// third of a product's flops) and one per solve block (12 blocks: the solve
// costs a product's flops).
constexpr std::size_t kGemmUnits = 12;
constexpr std::size_t kFactorUnits = 4;
constexpr int kSolveBlocks = 12;

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Which OpenBLAS kernels the solve runs on, and why (transport/blas_kernels.h).
// Without the measured rates: two bakes of the same scene and settings write
// the same manifest but for its timings.
TransportDecision blas_kernels_decision(const BlasKernels& k) {
  std::string why = k.why;
  if (k.candidate_gflops > 0.0)
    why += text_format(" in a %d x %d sgemm on one thread, timed in its CPU time",
                       BlasKernels::kProbeSize, BlasKernels::kProbeSize);
  return {"OpenBLAS kernels: " + k.used, why};
}

std::string channel_label(const std::vector<int>& rgb) {
  std::string s;
  for (int c : rgb) s += "RGB"[c];
  return s;
}

void validate_settings(const TransportSettings& s) {
  if (s.bounces < TransportSettings::kInfiniteBounces || s.bounces > TransportSettings::kMaxBounces)
    throw Error("transport.bounces", text_format("must be auto (0), infinity (-1) or 1..%d, got %d",
                                                 TransportSettings::kMaxBounces, s.bounces));
  if (!(s.auto_tolerance > 0.0 && s.auto_tolerance < 1.0))
    throw Error("transport.auto_tolerance",
                text_format("must be in (0, 1), got %g", s.auto_tolerance));
  if (s.max_auto_bounces < 1 || s.max_auto_bounces > TransportSettings::kMaxBounces)
    throw Error("transport.max_auto_bounces",
                text_format("must be in 1..%d, got %d", TransportSettings::kMaxBounces,
                            s.max_auto_bounces));
  if (!(s.auto_probe_min_seconds >= 0.0))
    throw Error("transport.auto_probe_min_seconds",
                text_format("must be >= 0, got %g", s.auto_probe_min_seconds));
}

// Rejects what would make the result meaningless; returns the largest row sum.
double validate_inputs(const FormFactorMatrix& f, const std::vector<glm::vec3>& albedo) {
  const std::size_t n = f.n;
  if (f.values.size() != n * n)
    throw Error("transport", text_format("form-factor matrix holds %zu values, expected %zu x %zu",
                                         f.values.size(), n, n));
  if (albedo.size() != n)
    throw Error("transport", text_format("%zu albedo values for %zu patches", albedo.size(), n));
  std::size_t non_finite = 0, negative = 0, first_bad = n * n;
  double max_row = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    double row = 0.0;
    for (std::size_t q = 0; q < n; ++q) {
      const float v = f.values[p * n + q];
      if (!std::isfinite(v)) {
        ++non_finite;
        first_bad = std::min(first_bad, p * n + q);
      } else if (v < 0.0f) {
        ++negative;
        first_bad = std::min(first_bad, p * n + q);
      } else {
        row += v;
      }
    }
    max_row = std::max(max_row, row);
  }
  if (non_finite + negative > 0)
    throw Error("transport",
                text_format("form-factor matrix has %zu NaN/Inf and %zu negative entries (first: "
                            "F[%zu][%zu] = %g); form factors must be finite and >= 0",
                            non_finite, negative, first_bad / n, first_bad % n,
                            static_cast<double>(f.values[first_bad])));
  for (std::size_t p = 0; p < n; ++p)
    for (int c = 0; c < 3; ++c) {
      const float a = albedo[p][c];
      if (!(a >= 0.0f && a <= 1.0f))
        throw Error("transport", text_format("albedo of patch %zu, channel %c, is %g: must be in "
                                             "[0, 1]",
                                             p, "RGB"[c], static_cast<double>(a)));
    }
  return max_row;
}

// Groups channels whose albedo agrees on every patch.
std::vector<std::vector<int>> channel_groups(const std::vector<glm::vec3>& albedo) {
  std::vector<std::vector<int>> groups;
  for (int c = 0; c < 3; ++c) {
    auto same = [&](int other) {
      return std::all_of(albedo.begin(), albedo.end(), [&](const glm::vec3& a) {
        return std::abs(a[c] - a[other]) <= kSameAlbedo;
      });
    };
    auto g = std::find_if(groups.begin(), groups.end(),
                          [&](const std::vector<int>& group) { return same(group.front()); });
    if (g != groups.end())
      g->push_back(c);
    else
      groups.push_back({c});
  }
  return groups;
}

// M = diag(rho_c) F: row p scaled by patch p's albedo in channel c.
MatrixValues scaled_rows(const FormFactorMatrix& f, const std::vector<glm::vec3>& albedo, int c) {
  const std::size_t n = f.n;
  MatrixValues m(n * n);
  for (std::size_t p = 0; p < n; ++p) {
    const float a = albedo[p][c];
    for (std::size_t q = 0; q < n; ++q) m[p * n + q] = a * f.values[p * n + q];
  }
  return m;
}

struct ChannelPlan {
  std::vector<int> rgb;
  std::string label;
  SpectralRadius radius;  // finite K only; K = infinity reads it off T
  bool infinite = false;
  SeriesPlan series;     // finite K
  int auto_bounces = 0;  // auto: where the series converged (0: not auto / not converged)
  double auto_next_fraction = 0.0;
  InverseMethod solve_method = InverseMethod::LU;  // expected for K = infinity, for costs
};

// F is known to float32 rounding (~1e-7 per row), so a radius this close to 1
// is 1 as far as the data can tell: the light would never settle, and a solve
// of the (numerically) singular I - M would return noise, not an error.
// Albedo 1 in a closed room lands here.
constexpr double kSettleMargin = 1e-6;

std::string divergence(const SpectralRadius& r, const std::vector<glm::vec3>& albedo, int c,
                       double max_row_sum) {
  float max_albedo = 0.0f;
  for (const glm::vec3& a : albedo) max_albedo = std::max(max_albedo, a[c]);
  return text_format(
      "spectral radius %.7f is 1 or more to the precision of F: no bounce returns less light "
      "than the one before (form-factor rows sum up to %.4f, albedo up to %.4f), so energy is "
      "not conserved",
      r.upper, max_row_sum, static_cast<double>(max_albedo));
}

// Auto: K where the series converges, or infinity. The series is a candidate
// only when its products, at one OpenBLAS product each, cost less than the
// exact solve; otherwise K = infinity is taken without timing any backend.
void plan_auto(ChannelPlan& plan, const float* m, std::size_t n, const TransportSettings& settings,
               std::vector<TransportDecision>& decisions) {
  const std::string who = "channel " + plan.label;
  const AutoBounces a =
      choose_auto_bounces(m, n, settings.auto_tolerance, settings.max_auto_bounces);
  if (!a.converged) {
    plan.infinite = true;
    decisions.push_back(
        {who + ": K = infinity (auto)",
         text_format("bounce %d still adds %.2e of the light so far (>= %.0e): the series "
                     "converges too slowly to truncate, solved exactly instead",
                     a.bounces + 1, a.next_fraction, settings.auto_tolerance)});
    return;
  }
  plan.auto_bounces = a.bounces;
  plan.auto_next_fraction = a.next_fraction;
  plan.series = plan_series(a.bounces);
  decisions.push_back(
      {who + text_format(": the series converges at K = %d (auto)", a.bounces),
       text_format("bounce %d adds %.2e of the light so far (< %.0e; light summed over "
                   "patches for unit light leaving each)",
                   a.bounces + 1, a.next_fraction, settings.auto_tolerance)});
  const double solve_cost = solve_cost_in_gemms(plan.solve_method, TransportPrecision::Float32);
  if (plan.series.gemms >= solve_cost) {
    plan.infinite = true;
    decisions.push_back(
        {who + ": K = infinity (auto)",
         text_format("the series to K = %d needs %d products, the float32 %s solve costs ~%.2g "
                     "OpenBLAS products; a product backend is timed only when the series could "
                     "win on OpenBLAS; the exact sum leaves nothing out",
                     a.bounces, plan.series.gemms, method_name(plan.solve_method), solve_cost)});
  }
}

// K for one channel, and for a finite K the spectral radius of M (its bound
// on what the omitted bounces add). K = infinity needs no power iteration:
// the radius is read off the solved T (spectral_radius_from_transport).
ChannelPlan plan_channel(const FormFactorMatrix& f, const std::vector<glm::vec3>& albedo,
                         std::vector<int> rgb, const TransportSettings& settings,
                         double max_row_sum, Diagnostics& diagnostics,
                         std::vector<TransportDecision>& decisions) {
  ChannelPlan plan;
  plan.rgb = std::move(rgb);
  plan.label = channel_label(plan.rgb);
  plan.solve_method = f.area.empty() ? InverseMethod::LU : InverseMethod::Cholesky;
  const std::string who = "channel " + plan.label;
  if (settings.bounces == TransportSettings::kInfiniteBounces) {
    plan.infinite = true;
    decisions.push_back({who + ": K = infinity", "requested"});
    return plan;
  }
  const MatrixValues m = scaled_rows(f, albedo, plan.rgb.front());
  if (settings.bounces == TransportSettings::kAutoBounces) {
    plan_auto(plan, m.data(), f.n, settings, decisions);
    if (plan.infinite) return plan;
  }
  plan.radius = estimate_spectral_radius(m.data(), f.n);
  plan.radius.weights = {};
  const SpectralRadius& r = plan.radius;
  decisions.push_back(
      {who + text_format(": spectral radius of diag(albedo) F = %.4f", r.estimate),
       text_format("power iteration, %d sgemv%s; Collatz-Wielandt bounds [%.4f, %.4f]",
                   r.iterations, r.converged ? "" : " (not converged)", r.lower, r.upper)});
  if (settings.bounces != TransportSettings::kAutoBounces)
    plan.series = plan_series(settings.bounces);
  if (r.estimate < 1.0 - kSettleMargin) {
    if (settings.bounces != TransportSettings::kAutoBounces)
      decisions.push_back({who + text_format(": K = %d", settings.bounces), "requested"});
    return plan;
  }
  const std::string why = divergence(r, albedo, plan.rgb.front(), max_row_sum);
  if (settings.bounces == TransportSettings::kAutoBounces)
    throw Error("transport.bounces",
                who + ": auto bounces cannot converge: " + why +
                    "; fix the form factors or ask for an explicit bounce count");
  diagnostics.warn(
      "transport.bounces",
      who + ": " + why +
          text_format("; the %d-bounce sum is finite but not physical", settings.bounces));
  decisions.push_back({who + text_format(": K = %d", settings.bounces), "requested"});
  return plan;
}

// Auto with a series candidate: the truncated series or the exact K =
// infinity, whichever costs less at the measured product rate.
void resolve_auto(ChannelPlan& plan, double gemm_cost, const std::string& gemm_name,
                  const TransportSettings& settings, Diagnostics& diagnostics,
                  std::vector<TransportDecision>& decisions) {
  if (plan.infinite || plan.auto_bounces == 0) return;
  const std::string who = "channel " + plan.label;
  const double series_cost = plan.series.gemms * gemm_cost;
  const double solve_cost = solve_cost_in_gemms(plan.solve_method, TransportPrecision::Float32);
  const char* method = method_name(plan.solve_method);
  if (solve_cost < series_cost) {
    plan.infinite = true;
    decisions.push_back(
        {who + ": K = infinity (auto)",
         text_format("cheaper than the series to K = %d: %d products on %s ~ %.2g OpenBLAS "
                     "products, the float32 %s solve ~ %.2g; the exact sum leaves nothing out",
                     plan.auto_bounces, plan.series.gemms, gemm_name.c_str(), series_cost, method,
                     solve_cost)});
    return;
  }
  decisions.push_back(
      {who + text_format(": K = %d (auto)", plan.auto_bounces),
       text_format("%d products on %s ~ %.2g OpenBLAS products, cheaper than the float32 %s "
                   "solve ~ %.2g",
                   plan.series.gemms, gemm_name.c_str(), series_cost, method, solve_cost)});
  diagnostics.left_out(
      "transport",
      who + text_format(": bounces after %d (the next adds %.2e of the light so "
                        "far, below the auto tolerance %.0e)",
                        plan.auto_bounces, plan.auto_next_fraction, settings.auto_tolerance));
}

// The decisions every finite K gets: what the omitted bounces could add, and
// how the series is summed.
void record_series(const ChannelPlan& plan, std::vector<TransportDecision>& decisions) {
  const std::string who = "channel " + plan.label;
  const int bounces = plan.series.bounces;
  decisions.push_back(
      {who + text_format(": bounces after %d could add at most %.3g of the first-hit light",
                         bounces, truncation_bound(plan.radius.upper, bounces)),
       text_format("c^(K+1) / (1 - c) with c = %.4f, the norm of diag(albedo) F in the max-norm "
                   "weighted by its Perron vector estimate",
                   plan.radius.upper)});
  if (bounces > 1)
    decisions.push_back(
        {who + text_format(": %d bounces by %s", bounces,
                           plan.series.scheme == SeriesScheme::Doubling ? "doubling" : "Horner"),
         text_format("%d products (Horner: %d, doubling: %d)", plan.series.gemms,
                     plan.series.horner_gemms, plan.series.doubling_gemms)});
}

std::size_t progress_units(const ChannelPlan& plan) {
  if (plan.infinite) return kFactorUnits + kSolveBlocks;
  return static_cast<std::size_t>(plan.series.gemms) * kGemmUnits;
}

void check_finite(const MatrixValues& t, std::size_t n, const std::string& label) {
  std::size_t bad = 0, first = t.size();
  for (std::size_t i = 0; i < t.size(); ++i)
    if (!std::isfinite(t[i])) {
      ++bad;
      first = std::min(first, i);
    }
  if (bad > 0)
    throw Error("transport", text_format("channel %s: the transport matrix has %zu NaN/Inf "
                                         "entries (first T[%zu][%zu]); it is not written",
                                         label.c_str(), bad, first / n, first % n));
}

// K = infinity for one channel: m (M) becomes T. The spectral radius and the
// divergence check come from T itself, no power iteration on M.
void solve_exactly(ChannelTransport& ct, MatrixValues& m, const ChannelPlan& plan,
                   const FormFactorMatrix& f, const std::vector<glm::vec3>& albedo,
                   double max_row_sum, Progress* progress, TransportExecutor* executor,
                   std::vector<TransportDecision>& decisions) {
  const std::size_t n = f.n;
  const int c = plan.rgb.front();
  std::vector<float> channel_albedo(n);
  for (std::size_t p = 0; p < n; ++p) channel_albedo[p] = albedo[p][c];
  InverseOptions options;
  options.solve_blocks = kSolveBlocks;
  options.area = f.area;
  if (!f.area.empty()) options.albedo = channel_albedo;
  bool factorised = false;
  options.tick = [&] {
    if (!progress) return;
    progress->advance(factorised ? 1 : kFactorUnits);
    factorised = true;
  };
  constexpr double kRadiusNotKnown = -1.0;
  InverseTransport inv;
  if (executor) {
    // The executor's interface takes and returns heap vectors.
    inv = executor->solve_infinite(std::vector<float>(m.begin(), m.end()), n, kRadiusNotKnown,
                                   options);
    m.assign(inv.t.begin(), inv.t.end());
    inv.t = {};
  } else {
    inv = solve_infinite_bounces_in_place(m.data(), n, kRadiusNotKnown, options);
  }
  const std::string who = "channel " + plan.label;
  const SpectralRadius r = spectral_radius_from_transport(m.data(), n);
  if (!(r.upper < 1.0 - kSettleMargin))
    throw Error("transport.bounces",
                who + ": K = infinity is impossible: " + divergence(r, albedo, c, max_row_sum) +
                    "; fix the form factors or ask for an explicit bounce count");
  ct.spectral_radius = r.estimate;
  ct.spectral_radius_lower = r.lower;
  ct.spectral_radius_upper = r.upper;
  ct.t = std::move(m);
  ct.bounces = TransportSettings::kInfiniteBounces;
  ct.auto_bounces = plan.auto_bounces;
  ct.precision = inv.precision;
  ct.condition_number = inv.condition;
  ct.flops = inv.flops;
  ct.method = std::string(method_name(inv.method)) + " " + precision_name(inv.precision);
  decisions.push_back(
      {who + text_format(": spectral radius of diag(albedo) F = %.4f", r.estimate),
       text_format("power iteration on the solved T, %d sgemv%s; Collatz-Wielandt bounds "
                   "[%.4f, %.4f]",
                   r.iterations, r.converged ? "" : " (not converged)", r.lower, r.upper)});
  if (inv.method == InverseMethod::Cholesky)
    decisions.push_back(
        {who + ": K = infinity by Cholesky of the symmetrised I - M",
         text_format("A F symmetric to %.2g (relative, largest entry); S positive definite, so "
                     "the spectral radius is below 1",
                     inv.asymmetry)});
  else if (!inv.lu_reason.empty())
    decisions.push_back({who + ": K = infinity by LU, not Cholesky", inv.lu_reason});
  else
    decisions.push_back({who + ": K = infinity by LU, not Cholesky",
                         executor ? "the distributed solve (ScaLAPACK) factorises by LU"
                                  : "F was not balanced ('closure_rays' 0): no patch areas make "
                                    "A F symmetric"});
  decisions.push_back(
      {who + text_format(": K = infinity by %s in %s, condition %.3g", method_name(inv.method),
                         precision_name(inv.precision), inv.condition),
       inv.why});
}

}  // namespace

const ChannelTransport& TransportResult::channel(int rgb) const {
  for (const ChannelTransport& c : channels)
    if (std::find(c.rgb.begin(), c.rgb.end(), rgb) != c.rgb.end()) return c;
  throw Error("transport", text_format("no transport matrix stands for channel %d", rgb));
}

TransportResult compute_transport(const FormFactorMatrix& form_factors,
                                  const std::vector<glm::vec3>& albedo,
                                  const TransportSettings& settings, Progress* progress,
                                  Diagnostics& diagnostics, TransportExecutor* executor) {
  const auto start = Clock::now();
  // Out of core (base/mapped_buffer.h): the work buffers stay on the heap,
  // each finished T goes to a mapped file.
  const std::optional<OutOfCorePolicy> out_of_core = out_of_core_policy();
  const OutOfCoreScope work_on_heap(std::nullopt);
  validate_settings(settings);
  const double max_row_sum = validate_inputs(form_factors, albedo);
  const std::size_t n = form_factors.n;
  TransportResult result;
  result.n = n;
  if (n == 0) {
    result.backend = "none (no patches)";
    return result;
  }
  result.decisions.push_back(blas_kernels_decision(choose_blas_kernels()));
  const FlushSubnormals flush_subnormals;
  result.decisions.push_back(
      {"subnormal floats flushed to zero in the solve",
       "below 1.2e-38, 31 decades under the light a bake resolves; on the open Sponza they made "
       "the Cholesky and inverse five times as long (transport/flush_subnormals.h)"});

  const std::vector<std::vector<int>> groups = channel_groups(albedo);
  result.grey = groups.size() == 1;
  if (result.grey) {
    result.decisions.push_back({"grey scene: one channel stands for R, G and B",
                                "every patch's albedo has r = g = b (within 1e-6)"});
    diagnostics.left_out("transport",
                         "G and B transport matrices: the scene is grey (every "
                         "albedo has r = g = b), the R matrix stands for all three");
  } else {
    for (const std::vector<int>& g : groups)
      if (g.size() > 1) {
        const std::string label = channel_label(g);
        result.decisions.push_back({"channels " + label + " share one matrix",
                                    "their albedos agree on every patch (within 1e-6)"});
        diagnostics.left_out("transport", text_format("a separate %c transport matrix: it equals "
                                                      "%c's (same albedo on every patch)",
                                                      label[1], label[0]));
      }
  }

  std::vector<ChannelPlan> plans;
  std::size_t gemms = 0;
  for (const std::vector<int>& g : groups) {
    if (progress) progress->check();
    plans.push_back(plan_channel(form_factors, albedo, g, settings, max_row_sum, diagnostics,
                                 result.decisions));
    if (!plans.back().infinite) gemms += static_cast<std::size_t>(plans.back().series.gemms);
  }

  std::unique_ptr<GemmBackend> own_gemm;
  GemmBackend* gemm = nullptr;
  if (executor)
    result.decisions.push_back({"dense algebra: " + executor->description(), "distributed bake"});
  if (executor && gemms > 0) {
    // The executor's products stand in for OpenBLAS: a product costs one.
    gemm = &executor->gemm();
    gemms = 0;
    for (ChannelPlan& plan : plans) {
      resolve_auto(plan, 1.0, gemm->name(), settings, diagnostics, result.decisions);
      if (plan.infinite) continue;
      record_series(plan, result.decisions);
      gemms += static_cast<std::size_t>(plan.series.gemms);
    }
  } else if (gemms > 0) {
    GemmSelection selection =
        select_gemm_backend(settings, n, gemms, diagnostics, result.decisions);
    own_gemm = std::move(selection.backend);
    gemm = own_gemm.get();
    result.probe_n = selection.probe_n;
    result.probe_openblas_seconds = selection.openblas_seconds;
    result.probe_clblast_seconds = selection.clblast_seconds;
    // A product's cost in OpenBLAS products: measured when Auto probed,
    // else taken as 1 (CLBlast requested without a probe).
    const bool probed_other = gemm->name() != "OpenBLAS" && selection.openblas_seconds > 0.0 &&
                              selection.clblast_seconds > 0.0;
    const double gemm_cost =
        probed_other ? selection.clblast_seconds / selection.openblas_seconds : 1.0;
    gemms = 0;
    for (ChannelPlan& plan : plans) {
      resolve_auto(plan, gemm_cost, gemm->name(), settings, diagnostics, result.decisions);
      if (plan.infinite) continue;
      record_series(plan, result.decisions);
      gemms += static_cast<std::size_t>(plan.series.gemms);
    }
  } else {
    for (const ChannelPlan& plan : plans)
      if (!plan.infinite) record_series(plan, result.decisions);  // K = 1
  }
  if (gemms == 0) {
    gemm = nullptr;
    result.backend = "none (no matrix product needed)";
  }
  std::size_t units = 0;
  for (const ChannelPlan& plan : plans) units += progress_units(plan);

  if (progress) progress->begin_stage("transport", std::max<std::size_t>(units, 1));
  for (const ChannelPlan& plan : plans) {
    const auto channel_start = Clock::now();
    if (progress) progress->check();
    ChannelTransport ct;
    ct.rgb = plan.rgb;
    MatrixValues m = scaled_rows(form_factors, albedo, plan.rgb.front());
    if (plan.infinite) {
      solve_exactly(ct, m, plan, form_factors, albedo, max_row_sum, progress, executor,
                    result.decisions);
    } else {
      ct.spectral_radius = plan.radius.estimate;
      ct.spectral_radius_lower = plan.radius.lower;
      ct.spectral_radius_upper = plan.radius.upper;
      ct.bounces = plan.series.bounces;
      ct.gemms = plan.series.gemms;
      ct.flops = plan.series.gemms * 2.0 * static_cast<double>(n) * static_cast<double>(n) *
                 static_cast<double>(n);
      ct.auto_bounces = plan.auto_bounces;
      ct.method = plan.series.scheme == SeriesScheme::Doubling ? "doubling" : "Horner";
      ct.truncation_bound = truncation_bound(plan.radius.upper, ct.bounces);
      if (plan.series.gemms == 0) {
        ct.t = std::move(m);  // K = 1: T = M
      } else {
        ct.t = sum_bounces(m, n, plan.series, *gemm, [&] {
          if (progress) progress->advance(kGemmUnits);
        });
      }
    }
    check_finite(ct.t, n, plan.label);
    // A finished channel is not read again until compression: out of core,
    // it goes to its file now and the next channel's work buffers get the
    // memory.
    if (out_of_core) ct.t = spill_to_file(std::move(ct.t), *out_of_core);
    ct.seconds = seconds_since(channel_start);
    result.flops += ct.flops;
    result.channels.push_back(std::move(ct));
  }
  if (gemm) result.backend = gemm->name();
  if (progress) progress->end_stage();
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace bounce
