#include "bake/vertex_light_error.h"

#include <string>

#include "base/error.h"
#include "runtime/compressed_transport.h"
#include "runtime/dense_transport.h"

namespace bounce {

IndirectLightError vertex_light_error(const FinalGather& gather, const SampleSet& samples,
                                      const PatchSet& patches,
                                      const std::vector<const float*>& exact,
                                      const CompressedMatrix& compressed,
                                      const IndirectLightProbe& probe) {
  const std::size_t n = compressed.n;
  if (gather.patches != n || patches.size() != n ||
      (gather.samples > 0 && gather.samples != samples.samples.size()))
    throw Error("vertex light error", "the final gather, patches and matrix do not match (" +
                                          std::to_string(gather.patches) + ", " +
                                          std::to_string(patches.size()) + ", " +
                                          std::to_string(n) + " patches)");
  if (exact.size() != static_cast<std::size_t>(compressed.channels))
    throw Error("vertex light error", "exact and compressed matrices differ in channel count");
  // T~ b through the run-time product's float32 loop: the decoded matrix's
  // product up to summation order, without decoding n x n entries per channel.
  const CompressedTransport approx(compressed, probe.channel_of_rgb, BlockLoop::kFloat32);
  // The vertices' irradiance from the patches' indirect light alone.
  const std::vector<glm::vec3> no_first_hit(samples.samples.size(), glm::vec3(0.0f));
  const auto gathered = [&](const std::vector<glm::vec3>& indirect, std::vector<glm::vec3>& out) {
    if (gather.samples > 0)
      gather.irradiance(indirect, sample_exitance(samples, patches, no_first_hit, indirect),
                        near_exitance(gather.near, nullptr, {}, {}, indirect), out);
    else
      gather.irradiance(indirect, out);
  };
  IndirectLightError e;
  std::vector<glm::vec3> t_exact, t_approx, v_exact, v_approx;
  for (const std::vector<glm::vec3>& b : probe.first_hit) {
    dense_indirect(exact, n, probe.channel_of_rgb, b, t_exact);
    approx.multiply(b, t_approx);
    gathered(t_exact, v_exact);
    gathered(t_approx, v_approx);
    double err2 = 0.0, ref2 = 0.0;
    for (std::size_t v = 0; v < v_exact.size(); ++v) {
      const glm::dvec3 d = glm::dvec3(v_approx[v]) - glm::dvec3(v_exact[v]);
      err2 += glm::dot(d, d);
      ref2 += glm::dot(glm::dvec3(v_exact[v]), glm::dvec3(v_exact[v]));
    }
    e.add_light(err2, ref2);
  }
  return e;
}

}  // namespace bounce
