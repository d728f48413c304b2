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

}  // namespace bounce
