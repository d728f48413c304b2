#include "transport/bounce_series.h"

#include <cblas.h>

#include <bit>
#include <cmath>
#include <limits>
#include <utility>

#include "base/error.h"
#include "transport/blas_int.h"

namespace bounce {

namespace {

// The steps of the doubling scheme after the leading binary digit of K.
enum class Step { Double, AddOne };

std::vector<Step> doubling_steps(int bounces) {
  std::vector<Step> steps;
  const unsigned k = static_cast<unsigned>(bounces);
  for (int bit = std::bit_width(k) - 2; bit >= 0; --bit) {
    steps.push_back(Step::Double);
    if (k & (1u << bit)) steps.push_back(Step::AddOne);
  }
  return steps;
}

// Whether a step after `s` reads P: any but a final AddOne, which forms
// M + M T without it.
bool p_needed_after(const std::vector<Step>& steps, std::size_t s) {
  const std::size_t left = steps.size() - s - 1;
  return left > 1 || (left == 1 && steps.back() == Step::Double);
}

// Products the doubling scheme needs; mirrors sum_doubling below.
int doubling_gemm_count(int bounces) {
  const std::vector<Step> steps = doubling_steps(bounces);
  int gemms = 0;
  bool p_is_m = true;
  for (std::size_t s = 0; s < steps.size(); ++s) {
    const bool p_needed_later = p_needed_after(steps, s);
    if (steps[s] == Step::Double) {
      gemms += (p_is_m || !p_needed_later) ? 1 : 2;
    } else {
      gemms += 1;
    }
    p_is_m = false;
  }
  return gemms;
}

void add_into(MatrixValues& t, const MatrixValues& p) {
  for (std::size_t i = 0; i < t.size(); ++i) t[i] += p[i];
}

MatrixValues sum_horner(const MatrixValues& m, std::size_t n, int bounces, GemmBackend& gemm,
                        const std::function<void()>& tick) {
  MatrixValues s = m, next(m.size());
  for (int h = 2; h <= bounces; ++h) {
    next = m;  // S_h = M + M S_(h-1)
    gemm.multiply(n, m.data(), s.data(), 1.0f, next.data());
    std::swap(s, next);
    if (tick) tick();
  }
  return s;
}

MatrixValues sum_doubling(const MatrixValues& m, std::size_t n, int bounces, GemmBackend& gemm,
                          const std::function<void()>& tick) {
  const std::vector<Step> steps = doubling_steps(bounces);
  // T_1 = M; P_1 = M is read from m itself until P is first formed.
  MatrixValues t = m, p(m.size()), tmp(m.size());
  bool p_is_m = true;
  auto product = [&](const MatrixValues& a, const MatrixValues& b, float beta) {
    gemm.multiply(n, a.data(), b.data(), beta, tmp.data());
    if (tick) tick();
  };
  for (std::size_t s = 0; s < steps.size(); ++s) {
    const bool p_needed_later = p_needed_after(steps, s);
    const MatrixValues& pk = p_is_m ? m : p;
    if (steps[s] == Step::Double) {
      if (p_is_m) {
        // k = 1: P_2 = M M and T_2 = M + P_2, one product for both.
        product(m, m, 0.0f);
        std::swap(p, tmp);
        add_into(t, p);
      } else {
        tmp = t;  // T_2k = T_k + P_k T_k
        product(pk, t, 1.0f);
        std::swap(t, tmp);
        if (p_needed_later) {
          product(pk, pk, 0.0f);  // P_2k = P_k P_k
          std::swap(p, tmp);
        }
      }
    } else if (s + 1 < steps.size()) {
      product(pk, m, 0.0f);  // P_(k+1) = P_k M, T_(k+1) = T_k + P_(k+1)
      std::swap(p, tmp);
      add_into(t, p);
    } else {
      tmp = m;  // last step: T_(k+1) = M + M T_k, no P needed
      product(m, t, 1.0f);
      std::swap(t, tmp);
    }
    p_is_m = false;
  }
  return t;
}

}  // namespace

SeriesPlan plan_series(int bounces) {
  if (bounces < 1) throw Error("transport", "a bounce series needs K >= 1");
  SeriesPlan plan;
  plan.bounces = bounces;
  plan.horner_gemms = bounces - 1;
  plan.doubling_gemms = doubling_gemm_count(bounces);
  plan.scheme =
      plan.doubling_gemms < plan.horner_gemms ? SeriesScheme::Doubling : SeriesScheme::Horner;
  plan.gemms = plan.scheme == SeriesScheme::Doubling ? plan.doubling_gemms : plan.horner_gemms;
  return plan;
}

MatrixValues sum_bounces(const MatrixValues& m, std::size_t n, const SeriesPlan& plan,
                         GemmBackend& gemm, const std::function<void()>& after_each_gemm) {
  if (m.size() != n * n) throw Error("transport", "sum_bounces: matrix size does not match n");
  return plan.scheme == SeriesScheme::Doubling
             ? sum_doubling(m, n, plan.bounces, gemm, after_each_gemm)
             : sum_horner(m, n, plan.bounces, gemm, after_each_gemm);
}

AutoBounces choose_auto_bounces(const float* m, std::size_t n, double tolerance, int max_bounces) {
  AutoBounces a;
  const int k = blas_dim(n, "cblas_sgemv");
  std::vector<float> v(n, 1.0f), w(n);
  double so_far = 0.0;
  for (int h = 1; h <= max_bounces + 1; ++h) {
    cblas_sgemv(CblasRowMajor, CblasNoTrans, k, k, 1.0f, m, k, v.data(), 1, 0.0f, w.data(), 1);
    std::swap(v, w);
    double e = 0.0;
    for (float x : v) e += x;
    a.energy.push_back(e);
    if (h >= 2) {
      a.bounces = h - 1;
      a.next_fraction = so_far > 0.0 ? e / so_far : 0.0;
      // `<=` so that a scene reflecting nothing (all zero) stops at K = 1.
      if (e <= tolerance * so_far) {
        a.converged = true;
        return a;
      }
    }
    so_far += e;
  }
  return a;
}

double truncation_bound(double norm_upper, int bounces) {
  if (!(norm_upper < 1.0)) return std::numeric_limits<double>::infinity();
  return std::pow(norm_upper, bounces + 1) / (1.0 - norm_upper);
}

}  // namespace bounce
