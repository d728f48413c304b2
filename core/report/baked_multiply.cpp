#include "report/baked_multiply.h"

#include "bake/stored_transport.h"

namespace bounce {

IndirectMultiply baked_multiply(const TransportResult& transport, const MatrixStorage& storage,
                                std::shared_ptr<void>& /*keep_alive*/) {
  return TransportMultiplier(stored_transport(transport, storage), MultiplyChoice::kAutoCpu,
                             CppLoop::kMeasured)
      .multiply();
}

}  // namespace bounce
