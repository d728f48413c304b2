#include "report/baked_multiply.h"

#include "runtime/compressed_transport.h"
#include "runtime/dense_transport.h"

namespace bounce {

IndirectMultiply baked_multiply(const TransportResult& transport, const MatrixStorage& storage,
                                std::shared_ptr<void>& keep_alive) {
  if (!storage.compressed) {
    const std::vector<const float*> dense = stored_channels(transport);
    const std::size_t n = transport.n;
    const auto map = channel_of_rgb(transport);
    return [dense, n, map](const std::vector<glm::vec3>& in, std::vector<glm::vec3>& out) {
      dense_indirect(dense, n, map, in, out);
    };
  }
  auto cpp = std::make_shared<CompressedTransport>(*storage.compressed, channel_of_rgb(transport));
  keep_alive = cpp;
  return [cpp](const std::vector<glm::vec3>& in, std::vector<glm::vec3>& out) {
    cpp->multiply(in, out);
  };
}

}  // namespace bounce
