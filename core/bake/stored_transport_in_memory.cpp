// The in-memory overload of stored_transport (bake/stored_transport.h): a
// bake that was just made, before it is written. In a file of its own, so
// that reading a bake folder back (bounce_runtime) does not link the
// compression stage that MatrixStorage belongs to.
#include "bake/stored_transport.h"

namespace bounce {

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
