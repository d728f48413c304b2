// engine BAKE PATCH_LIGHT: what an engine does with the runtime alone. It
// computes the direct light b on the bake's patches itself (here it takes the
// b column of `bounce solve`'s patch_light.npy, n x [E, b, T b]), and the
// runtime reads the bake and multiplies its matrix: T b, checked against the
// T b column. Exit 1 when they differ by more than float rounding.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <vector>

#include <bounce/bake_folder.h>
#include <bounce/relight.h>

namespace {

// The largest |T b - expected| and |expected| over the patches, expected
// being the T b column of `solved`.
int check(const bounce::LoadedBake& bake, const std::vector<float>& solved) {
  const std::size_t n = bake.size();
  if (solved.size() != 9 * n) return std::fprintf(stderr, "engine: not n x 3 x 3\n"), 1;
  std::vector<glm::vec3> b(n), tb(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) b[i][c] = solved[9 * i + 3 + c];
  const bounce::TransportMultiplier multiplier(
      bounce::stored_transport(bake), bounce::MultiplyChoice::kAutoCpu, bounce::CppLoop::kFloat32);
  multiplier.multiply()(b, tb);
  double worst = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const double expected = solved[9 * i + 6 + c];
      worst = std::max(worst, std::abs(double(tb[i][c]) - expected));
      largest = std::max(largest, std::abs(expected));
    }
  std::printf("%zu patches, T b with %s: largest |T b| %.6g, largest difference %.3g\n", n,
              multiplier.what().c_str(), largest, worst);
  return worst <= 1e-5 * largest ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) return std::fprintf(stderr, "usage: engine BAKE PATCH_LIGHT\n"), 2;
  try {
    return check(bounce::BakeReader::read(argv[1], bounce::BakeReader::Dense::kIfNotCompressed),
                 bounce::read_npy_f32(argv[2]).data);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "engine: %s\n", e.what());
    return 1;
  }
}
