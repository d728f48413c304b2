#pragma once
// Public: the compressed transport matrix, how it was stored and what the
// compression changes.
//
//   const bounce::BakeResult result = bounce::Baker(scene, settings, diagnostics).run(progress);
//   const bounce::MatrixStorage& storage = result.storage;  // dense or compressed, and why
//   bounce::decompress_channel(*storage.compressed, channel, dense_out);
//
// The codec's settings and the compressed matrix (kept entries exact, the rest
// log-quantised and block-encoded), the storage decision of a bake, the
// errors compression causes (per entry, on the indirect light) and the
// pictures of a matrix and of its error that the bake folder and the
// studio's views show. For a front end that compresses a matrix itself as a
// bake does: the entries' importance to the light (light_importance, which
// CodecSettings::importance weighs the encoding by), compress_for_light
// (compress, measure, and try the lights rebalanced), and the row and column
// orderings before block encoding (our_ordering, paper_ordering) with the
// cost that compares them (block_spread_cost). For a view that explains one
// patch's error: row_error_contributions, the blocks and kept entries of its
// row ranked by how much of the difference they make. For a view that draws
// a matrix's error: compression_error_maps, its pictures and the numbers
// under them in one call.
#include "bake/matrix_storage.h"
#include "compress/codec.h"
#include "compress/compression_error.h"
#include "compress/compression_error_maps.h"
#include "compress/entry_importance.h"
#include "compress/light_rebalance.h"
#include "compress/matrix_picture.h"
#include "compress/ordering.h"
#include "compress/row_error_contributions.h"
