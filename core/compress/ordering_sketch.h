#pragma once
// A short vector per patch that stands in for its full row (and column) of
// the quantised transport image when ordering: distances between sketches
// approximate distances between rows, at dims floats instead of
// n * channels bytes per patch.
//
// Which sketch. Patch order in a real matrix is voxel order, coherent only in
// part, and in the worst case random; a block-averaged downsample of a row
// over consecutive columns then averages unrelated patches and keeps little
// more than the row mean. A random projection (Johnson-Lindenstrauss) keeps
// distances whatever the order, but with a relative noise of about
// sqrt(2 / dims) per distance (18% at 64 dims), which scrambles the close
// neighbours that matter. Rows of a transport matrix in log codes are smooth
// functions of the receiver position (a code is an affine function of the log
// of a smooth kernel), so their centred covariance has a fast-decaying
// spectrum: the projection on the top principal directions keeps nearly all
// of each distance, with no random noise (the error is the discarded
// variance only, reported as `captured`).
//
// How. Randomised range finder (Halko, Martinsson, Tropp 2011, algorithms 4.1
// and 5.1) on M = [A | A^T] (row i of M: row i of the image followed by column
// i, all channels, n x 2*n*channels; with use_columns = false just A):
//   pass 1  Y = M Omega (Omega: +-1, k = dims + oversampling columns), centred
//           (centring Y centres M without knowing its mean first);
//           Q = orthonormal basis of Y (modified Gram-Schmidt twice, double);
//   pass 2  B = Q^T M, G = B B^T = U diag(lambda) U^T (k x k);
//   sketch  S = Q U diag(sqrt(lambda)), first dims columns.
// ||S_a - S_b|| is the distance between the projections of centred rows a and
// b of M. The image is read twice, in panels of rows converted to float; all
// products are sgemm (OpenBLAS), 4 * 2 * n^2 * channels * k flops in all
// (~2.5e11 at n = 16384, k = 40: seconds on two cores). Memory besides the
// image: a float panel (~24 MB) and a few n x k arrays.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace bounce {

struct SketchSettings {
  std::size_t dims = 32;         // sketch length (clamped to n - 1)
  std::size_t oversampling = 8;  // extra random vectors for the range finder
  bool use_columns = true;       // sketch [row i | column i], not just row i
  std::uint64_t seed = 1;        // Omega's random stream
  // Code 0 marks a hole (an entry kept exactly elsewhere, don't-care for the
  // block encoder): read it as 255. Holes are the largest entries, so the
  // top code continues the row's profile, where a 0 would put a spike of
  // -255 into every distance (measured: the sketch then keeps only ~70% of
  // the energy and orders worse than the paper's tour).
  bool zero_is_hole = false;
};

struct Sketch {
  std::size_t n = 0;
  std::size_t dims = 0;
  std::vector<float> coords;      // n x dims, row-major, principal axis first
  std::vector<double> variances;  // per sketch axis: sum over patches of coord^2
  double captured = 1.0;          // fraction of the centred energy of M kept
};

// Deterministic for a given seed and thread count (sgemm's summation order
// may depend on the latter).
Sketch principal_sketch(const std::uint8_t* image, std::size_t n, std::size_t channels,
                        const SketchSettings& settings);

}  // namespace bounce
