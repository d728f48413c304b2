#include "runtime/transport_multiplier.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>

#include "base/diagnostics.h"
#include "base/error.h"
#include "compute/opencl_context.h"
#include "runtime/compressed_transport.h"
#include "runtime/compressed_transport_cl.h"
#include "runtime/dense_transport.h"
#include "transport/blas_kernels.h"

namespace bounce {

namespace {

// Products each candidate loop runs at load (after one that warms its
// caches), taking the fastest; and how much faster the float32 loop must
// be to replace the bfloat16 one, so that timing noise on a busy machine
// does not flip a choice between two loops of about the same speed.
constexpr int kMeasuredProducts = 3;
constexpr double kFloat32Margin = 1.1;

double best_product_seconds(const CompressedTransport& t, const std::vector<glm::vec3>& b,
                            std::vector<glm::vec3>& out) {
  using Clock = std::chrono::steady_clock;
  t.multiply(b, out);
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < kMeasuredProducts; ++k) {
    const auto start = Clock::now();
    t.multiply(b, out);
    best = std::min(best, std::chrono::duration<double>(Clock::now() - start).count());
  }
  return best;
}

// The C++ product with the loop `loop` asks for. The bfloat16 loop's
// rounding is about 170x below the compression error (docs/benchmarks.md,
// runtime), so it is kept whenever it is not clearly the slower.
std::shared_ptr<CompressedTransport> cpp_product(const StoredTransport& t, CppLoop loop) {
  if (loop == CppLoop::kFloat32 || !CompressedTransport::has_bf16_loop())
    return std::make_shared<CompressedTransport>(
        *t.compressed, t.channel_of_rgb,
        loop == CppLoop::kFloat32 ? BlockLoop::kFloat32 : BlockLoop::kFastest);
  CompressedTransportTables tables =
      build_compressed_transport_tables(*t.compressed, t.channel_of_rgb);
  auto fastest = std::make_shared<CompressedTransport>(tables, BlockLoop::kFastest);
  if (std::string(fastest->block_loop()) != "avx512-bf16") return fastest;  // BC4: one loop
  auto float32 = std::make_shared<CompressedTransport>(std::move(tables), BlockLoop::kFloat32);
  const std::vector<glm::vec3> b(t.n, glm::vec3(1.0f));
  std::vector<glm::vec3> out;
  const double bf16_seconds = best_product_seconds(*fastest, b, out);
  const double float32_seconds = best_product_seconds(*float32, b, out);
  return float32_seconds * kFloat32Margin < bf16_seconds ? float32 : fastest;
}

}  // namespace

const char* multiply_choice_name(MultiplyChoice choice) {
  switch (choice) {
    case MultiplyChoice::kAuto:
    case MultiplyChoice::kAutoCpu:
      return "auto";
    case MultiplyChoice::kOpenCl:
      return "opencl";
    case MultiplyChoice::kCpp:
      return "cpp";
    case MultiplyChoice::kDense:
      return "dense";
  }
  return "auto";
}

std::optional<MultiplyChoice> multiply_choice_from_name(const std::string& name) {
  for (const MultiplyChoice c : {MultiplyChoice::kAuto, MultiplyChoice::kOpenCl,
                                 MultiplyChoice::kCpp, MultiplyChoice::kDense})
    if (name == multiply_choice_name(c)) return c;
  return std::nullopt;
}

bool opencl_device_is_gpu() {
  try {
    cl_device_type type = 0;
    clGetDeviceInfo(OpenClContext::shared().device(), CL_DEVICE_TYPE, sizeof(type), &type, nullptr);
    return (type & CL_DEVICE_TYPE_GPU) != 0;
  } catch (const Error&) {
    return false;  // no OpenCL at all
  }
}

TransportMultiplier::TransportMultiplier(const StoredTransport& t, MultiplyChoice choice,
                                         CppLoop loop, Diagnostics* diagnostics) {
  const bool compressed = t.compressed != nullptr;
  const bool automatic = choice == MultiplyChoice::kAuto || choice == MultiplyChoice::kAutoCpu;
  if (choice == MultiplyChoice::kDense || (!compressed && automatic)) {
    if (t.dense.empty())
      throw Error(t.where, choice == MultiplyChoice::kDense
                               ? "holds no dense T.npy, which the dense product needs (bake with "
                                 "'codec' dense or with 'dump_matrices')"
                               : "holds neither a compressed nor a dense transport matrix");
    // Here, not in the frame: the choice may re-initialise OpenBLAS.
    choose_blas_kernels();
    const std::vector<const float*> dense = t.dense;
    const std::size_t n = t.n;
    const auto map = t.channel_of_rgb;
    multiply_ = [dense, n, map](const std::vector<glm::vec3>& in, std::vector<glm::vec3>& out) {
      dense_indirect(dense, n, map, in, out);
    };
    multiply_into_ = [dense, n, map](std::span<const glm::vec3> in, std::span<glm::vec3> out) {
      dense_indirect(dense, n, map, in, out);
    };
    what_ = "dense float32 (OpenBLAS sgemv)";
    return;
  }
  if (!compressed)
    throw Error(t.where, std::string("holds no compressed matrix (T.dds) for the product ") +
                             multiply_choice_name(choice));
  const bool opencl = choice == MultiplyChoice::kOpenCl ||
                      (choice == MultiplyChoice::kAuto && opencl_device_is_gpu());
  if (opencl) {
    try {
      auto cl = std::make_shared<ClCompressedTransport>(*t.compressed, t.channel_of_rgb);
      what_ = "compressed, OpenCL on " + cl->device_name();
      multiply_ = [cl](const std::vector<glm::vec3>& in, std::vector<glm::vec3>& out) {
        cl->multiply(in, out);
      };
      multiply_into_ = [cl](std::span<const glm::vec3> in, std::span<glm::vec3> out) {
        cl->multiply(in, out);
      };
      return;
    } catch (const Error& e) {
      if (choice == MultiplyChoice::kOpenCl) throw;
      if (diagnostics)
        diagnostics->warn("solve", std::string("OpenCL failed, using the C++ path: ") + e.what());
    }
  }
  std::shared_ptr<CompressedTransport> cpp = cpp_product(t, loop);
  what_ = std::string("compressed, C++ (") + cpp->block_loop() + ")";
  multiply_ = [cpp](const std::vector<glm::vec3>& in, std::vector<glm::vec3>& out) {
    cpp->multiply(in, out);
  };
  multiply_into_ = [cpp](std::span<const glm::vec3> in, std::span<glm::vec3> out) {
    cpp->multiply(in, out);
  };
}

}  // namespace bounce
