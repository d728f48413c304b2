#pragma once
// A bake's matrices as the runtime multiplies them
// (runtime/transport_multiplier.h), from a bake folder read back or from a
// bake still in memory. The result points into its argument.
#include "bake/bake.h"
#include "folder/bake_reader.h"
#include "runtime/transport_multiplier.h"

namespace bounce {

StoredTransport stored_transport(const LoadedBake& bake);
// A bake in memory: the compressed matrix when it has one, else the dense
// matrices.
StoredTransport stored_transport(const TransportResult& transport, const MatrixStorage& storage);

}  // namespace bounce
