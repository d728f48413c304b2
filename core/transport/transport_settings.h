#pragma once
// What the user chooses for the multi-bounce stage (`--bounces`, backend).
namespace bounce {

struct TransportSettings {
  // 0 = auto (stop when the next bounce adds less than auto_tolerance of the
  // light so far), kInfiniteBounces = K -> infinity by LU, 1..kMaxBounces = that many bounces.
  static constexpr int kAutoBounces = 0;
  static constexpr int kInfiniteBounces = -1;
  static constexpr int kMaxBounces = 64;
  int bounces = kAutoBounces;
  double auto_tolerance = 1e-3;
  // Auto switches to K = infinity when the series has not converged by then.
  int max_auto_bounces = kMaxBounces;
  // Auto times one product on each backend (once per process and size) and
  // keeps the faster; CLBlast falls back to OpenBLAS with a warning when
  // OpenCL has no device or CLBlast fails.
  enum class Backend { Auto, OpenBLAS, CLBlast };
  Backend backend = Backend::Auto;
  // Auto probes CLBlast only when the products are predicted to take at least
  // this long on OpenBLAS: the probe's first CLBlast call compiles kernels
  // (0.3 s with PoCL's kernel cache warm, 15-20 s cold), more than a small
  // problem could ever gain.
  double auto_probe_min_seconds = 1.0;
};

}  // namespace bounce
