#pragma once
// The product T b of a bake's stored matrix, chosen once: the compressed
// matrix on the OpenCL device, the compressed matrix in C++, or the dense
// float32 matrix. Every front end that lights a bake (`bounce solve`, the
// report, `bake --reference`, the studio's preview) asks here rather than
// building a multiplier itself, so they all pick the same way.
//
// The C++ block loop is picked by a short measurement when the matrix is
// laid out: where the CPU has the bfloat16 loop, both it and the float32
// loop run a few products and the bfloat16 loop is kept unless the float32
// one is clearly faster. The CPU's features alone do not decide it: on some
// AVX-512 machines the bfloat16 loop is the slower of the two.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "compress/codec.h"
#include "runtime/patch_lighting.h"

namespace bounce {

class Diagnostics;

// A bake's matrices as the runtime multiplies them; LoadedBake
// (folder/bake_reader.h) and BakeResult (bake/bake.h) both describe theirs so.
struct StoredTransport {
  std::size_t n = 0;
  std::array<int, 3> channel_of_rgb{0, 1, 2};
  const CompressedMatrix* compressed = nullptr;  // null: the bake stored none
  std::vector<const float*> dense;               // stored channels, n x n; empty: not held
  std::string where;                             // names the bake in errors
};

enum class MultiplyChoice {
  kAuto,     // a dense bake: dense; else OpenCL on a GPU, otherwise C++
  kAutoCpu,  // as kAuto without OpenCL: the compressed C++ product, else dense
  kOpenCl,   // the compressed matrix on the OpenCL device
  kCpp,      // the compressed matrix in C++
  kDense,    // the dense float32 matrix (OpenBLAS sgemv)
};

// "auto", "opencl", "cpp", "dense": the names of `bounce solve --multiply`
// (kAutoCpu is "auto" too); from_name gives nullopt for any other name.
const char* multiply_choice_name(MultiplyChoice choice);
std::optional<MultiplyChoice> multiply_choice_from_name(const std::string& name);

// The C++ block loop: picked by measurement (above), or float32 always.
enum class CppLoop { kMeasured, kFloat32 };

class TransportMultiplier {
 public:
  // Throws bounce::Error naming `t.where` when the matrix the choice needs
  // is not there. kAuto falls back from a failing OpenCL device to C++ with
  // a warning in `diagnostics` (when given); kOpenCl throws instead.
  TransportMultiplier(const StoredTransport& t, MultiplyChoice choice, CppLoop loop,
                      Diagnostics* diagnostics = nullptr);

  // In words, e.g. "compressed, C++ (avx512-bf16)" or "dense float32
  // (OpenBLAS sgemv)".
  const std::string& what() const { return what_; }
  // The product, into vectors or into caller-owned memory (a frame graph's
  // arena). Each owns what it multiplies with (copies share it), so it
  // outlives this object; a dense product reads the matrices of the
  // StoredTransport, which must outlive it.
  const IndirectMultiply& multiply() const { return multiply_; }
  const IndirectMultiplySpan& multiply_into() const { return multiply_into_; }

 private:
  std::string what_;
  IndirectMultiply multiply_;
  IndirectMultiplySpan multiply_into_;
};

// Whether the OpenCL device is a GPU (false without OpenCL): kAuto uses
// OpenCL only there, since on a CPU device the kernel shares the cores with
// the C++ product and loses to it.
bool opencl_device_is_gpu();

}  // namespace bounce
