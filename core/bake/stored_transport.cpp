#include "bake/stored_transport.h"

namespace bounce {

StoredTransport stored_transport(const LoadedBake& bake) {
  StoredTransport t;
  t.n = bake.size();
  t.channel_of_rgb = bake.channel_of_rgb;
  t.compressed = bake.compressed ? &*bake.compressed : nullptr;
  for (const auto& m : bake.dense) t.dense.push_back(m.data());
  t.where = bake.dir.string();
  return t;
}

StoredTransport stored_transport(const TransportResult& transport, const MatrixStorage& storage) {
  StoredTransport t;
  t.n = transport.n;
  t.channel_of_rgb = channel_of_rgb(transport);
  t.compressed = storage.compressed ? &*storage.compressed : nullptr;
  if (!storage.compressed) t.dense = stored_channels(transport);
  t.where = "the bake";
  return t;
}

}  // namespace bounce
