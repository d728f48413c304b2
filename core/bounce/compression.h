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
// studio's views show.
#include "bake/matrix_storage.h"
#include "compress/codec.h"
#include "compress/compression_error.h"
#include "compress/matrix_picture.h"
