// The far-field sums of the form factors (formfactor/far_field.h): the C++
// path against a naive double-precision loop, the OpenCL path
// (formfactor/far_field_cl.h) against the C++ one, and (disabled, run by
// hand) the two timed against each other at the size of the Cornell box at
// voxel 16.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "base/error.h"
#include "formfactor/far_field.h"
#include "formfactor/far_field_cl.h"

namespace bounce {
namespace {

// n patches of 1..max_points points (exactly max_points when `full`) in the
// unit cube, random unit normals, areas in [0.001, 0.01]: about a quarter of
// the point pairs face each other, as on walls facing across a room.
FarPoints random_points(std::size_t n, std::uint32_t max_points, bool full, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), signed_unit(-1.0f, 1.0f),
      area(0.001f, 0.01f);
  std::uniform_int_distribution<std::uint32_t> count(1, max_points);
  FarPoints f;
  f.offsets.push_back(0);
  for (std::size_t p = 0; p < n; ++p) {
    const std::uint32_t k = full ? max_points : count(rng);
    for (std::uint32_t i = 0; i < k; ++i) {
      f.positions.emplace_back(unit(rng), unit(rng), unit(rng));
      glm::vec3 normal(0.0f);
      while (!(glm::length(normal) > 0.1f))
        normal = glm::vec3(signed_unit(rng), signed_unit(rng), signed_unit(rng));
      f.normals.push_back(glm::normalize(normal));
      f.areas.push_back(area(rng));
    }
    f.offsets.push_back(f.offsets.back() + k);
  }
  return f;
}

// The definition, in double precision, written independently of the code
// under test.
std::vector<double> naive_sums(const FarPoints& f) {
  const std::size_t n = f.patches();
  std::vector<double> sums(n * n, 0.0);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = p; q < n; ++q)
      for (std::uint32_t i = f.offsets[p]; i < f.offsets[p + 1]; ++i)
        for (std::uint32_t j = f.offsets[q]; j < f.offsets[q + 1]; ++j) {
          if (i == j) continue;
          const glm::dvec3 d = glm::dvec3(f.positions[j]) - glm::dvec3(f.positions[i]);
          const double r2 = glm::dot(d, d);
          const double cos_i = glm::dot(glm::dvec3(f.normals[i]), d);
          const double cos_j = -glm::dot(glm::dvec3(f.normals[j]), d);
          if (cos_i <= 0.0 || cos_j <= 0.0 || !(r2 > 0.0)) continue;
          sums[p * n + q] += static_cast<double>(f.areas[i]) * f.areas[j] * cos_i * cos_j /
                             (std::numbers::pi * r2 * r2);
        }
  return sums;
}

bool opencl_device(std::string& why) {
  try {
    far_field_device_name();
    return true;
  } catch (const Error& e) {
    why = e.what();
    return false;
  }
}

// Relative 1e-5 of each sum; the absolute floor (1e-6 of the largest sum)
// covers a point pair that lies on the facing threshold, whose tiny term one
// precision counts and the other does not.
template <class A, class B>
void expect_close(const std::vector<A>& got, const std::vector<B>& want, const char* what) {
  ASSERT_EQ(got.size(), want.size());
  double largest = 0.0;
  for (const B w : want) largest = std::max(largest, std::abs(static_cast<double>(w)));
  ASSERT_GT(largest, 0.0);
  int reported = 0;
  for (std::size_t k = 0; k < got.size(); ++k) {
    const double g = got[k], w = want[k];
    const double tolerance = 1e-5 * std::abs(w) + 1e-6 * largest;
    if (std::abs(g - w) > tolerance && reported++ < 10)
      ADD_FAILURE() << what << ": entry " << k << " is " << g << ", expected " << w;
  }
  EXPECT_EQ(reported, 0) << what << ": entries out of tolerance";
}

TEST(FarField, CppSumsEqualNaiveDoubleLoop) {
  const FarPoints f = random_points(70, 8, false, 1);
  const std::vector<float> sums = far_field_sums(f);
  expect_close(sums, naive_sums(f), "C++ vs double");
  // Below the diagonal: nothing.
  const std::size_t n = f.patches();
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = 0; q < p; ++q) EXPECT_EQ(sums[p * n + q], 0.0f);
}

TEST(FarField, OpenClSumsEqualCppSums) {
  std::string why;
  if (!opencl_device(why)) GTEST_SKIP() << "no OpenCL device: " << why;
  // 70 patches: not a multiple of the kernel's 16 x 16 tile, so the range
  // has work-items past the end.
  for (const unsigned seed : {1u, 2u}) {
    const FarPoints f = random_points(70, 8, false, seed);
    expect_close(far_field_sums_cl(f), far_field_sums(f), "OpenCL vs C++");
  }
}

TEST(FarField, EmptyAndInconsistentInputs) {
  EXPECT_TRUE(far_field_sums(FarPoints{}).empty());
  FarPoints f = random_points(3, 2, true, 3);
  f.areas.pop_back();
  EXPECT_THROW(far_field_sums(f), Error);
  f = random_points(3, 2, true, 3);
  f.offsets[1] = 5;  // beyond offsets[2]
  EXPECT_THROW(far_field_sums(f), Error);
  std::string why;
  if (opencl_device(why)) {
    EXPECT_TRUE(far_field_sums_cl(FarPoints{}).empty());
    EXPECT_THROW(far_field_sums_cl(f), Error);
  }
}

template <class F>
double best_ms(int runs, F&& f) {
  double best = 1e300;
  for (int r = 0; r < runs; ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    best = std::min(
        best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                  .count());
  }
  return best;
}

// Run by hand (docs/benchmarks.md, "Far-field form factors: OpenCL vs C++"):
//   build/release/tests/bounce_unit_tests --gtest_also_run_disabled_tests
//       --gtest_filter='FarField.DISABLED_*'
// 4000 patches x 8 points: the size of the Cornell box at voxel 16.
TEST(FarField, DISABLED_TimeOpenClAgainstCpp) {
  std::string why;
  if (!opencl_device(why)) GTEST_SKIP() << "no OpenCL device: " << why;
  const FarPoints f = random_points(4000, 8, true, 7);
  std::vector<float> cpp, cl;
  // Warm-up: the kernel build (cached), first touches of the memory.
  cpp = far_field_sums(f);
  cl = far_field_sums_cl(f);
  const double cpp_ms = best_ms(5, [&] { cpp = far_field_sums(f); });
  const double cl_ms = best_ms(5, [&] { cl = far_field_sums_cl(f); });
  std::printf(
      "far field, %zu patches x 8 points, device %s:\n  C++ (OpenMP)  %9.1f ms\n  OpenCL        "
      "%9.1f ms  (upload, kernel, read-back)\n  OpenCL / C++  %9.2fx\n",
      f.patches(), far_field_device_name().c_str(), cpp_ms, cl_ms, cl_ms / cpp_ms);
  expect_close(cl, cpp, "OpenCL vs C++");
}

}  // namespace
}  // namespace bounce
