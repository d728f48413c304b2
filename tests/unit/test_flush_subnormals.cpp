// Subnormals flushed within the scope, on this thread and on OpenBLAS's
// worker threads (a product large enough to be split among them), and made
// again once the scope ends.
#include <gtest/gtest.h>

#include <cblas.h>

#include <algorithm>
#include <vector>

#include "transport/flush_subnormals.h"

namespace bounce {

namespace {

// Every entry of a 512 x 512 product whose terms are 1e-40 each (subnormal)
// and whose sums, 512 of them, are 5.12e-38 (normal) where nothing flushes.
std::vector<float> product_of_subnormal_terms() {
  constexpr int n = 512;
  const std::vector<float> a(std::size_t{n} * n, 1e-20f);
  std::vector<float> c(a.size(), -1.0f);
  cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, n, n, n, 1.0f, a.data(), n, a.data(), n,
              0.0f, c.data(), n);
  return c;
}

float tiny_product() {
  volatile float a = 1e-30f, b = 1e-10f;
  return a * b;
}

}  // namespace

TEST(FlushSubnormals, FlushesHereAndInBlasThreadsThenRestores) {
  EXPECT_GT(tiny_product(), 0.0f);
  {
    const FlushSubnormals flush;
    EXPECT_EQ(tiny_product(), 0.0f);
    const std::vector<float> c = product_of_subnormal_terms();
    EXPECT_EQ(*std::max_element(c.begin(), c.end()), 0.0f);
    EXPECT_EQ(*std::min_element(c.begin(), c.end()), 0.0f);
  }
  EXPECT_GT(tiny_product(), 0.0f);
  const std::vector<float> c = product_of_subnormal_terms();
  EXPECT_GT(*std::min_element(c.begin(), c.end()), 5e-38f);
}

}  // namespace bounce
