#pragma once
// Patch-to-patch form factors F_PQ = G_PQ V_PQ / A_P, with G_PQ the energy
// leaving P that reaches Q and V_PQ the visible fraction. Each unordered pair
// is computed once (both directions, one set of visibility rays).
//
// Far pairs (centroids `near_cells` voxels apart or more): the differential
// kernel summed over at most `far_representatives` points per patch, each the
// area centroid of a group of the pieces of surface the patch stands for; the
// kernel is smooth there (furnace rows close to 1% with 8 points, no better
// with 64).
// Near pairs: every member sample of one patch against the surface the other
// patch stands for -- the triangle parts (clipped polygons) its samples carry
// -- with the exact point-to-polygon form factor where a part is large
// against its distance. A sample's form factors to the surrounding polygons
// then add up to at most 1, as they must: this is what keeps rows near edges
// and corners closed (row sums <= 1). The far field is reciprocal exactly;
// near pairs up to the point quadrature of the source side, which the
// manifest reports as the reciprocity error.
// Visibility V_PQ: `visibility_rays` rays between member pairs picked evenly
// from the pairs that face each other, weighted by their kernel value, traced
// in batches with Embree's stream API. Rays start and end on the surface (a
// piece of each far point's group picked by area), never at a far point
// itself: a mean of pieces of two layers 1 cm apart (a light under a ceiling
// in one voxel patch) lies between them, where every ray is blocked.
#include <cstdint>
#include <vector>

#include "base/mapped_buffer.h"
#include "base/progress.h"
#include "patches/patch_set.h"
#include "raytrace/ray_tracer.h"
#include "voxel/voxelization.h"

namespace bounce {

struct FormFactorSettings {
  int visibility_rays = 8;
  int far_representatives = 8;
  float near_cells = 2.5f;
  // Rows of the upper triangle this process computes: p = row_offset,
  // row_offset + row_stride, ... (core/distributed deals them out to MPI
  // ranks; row p pairs with every q >= p, so dealing rows cyclically evens out
  // the work). Every entry depends on its pair only, so the rows computed
  // anywhere are bit-identical to the same rows of the full computation; rows
  // not computed stay 0 (both F_pq and F_qp for q >= p).
  std::size_t row_offset = 0;
  std::size_t row_stride = 1;
};

// Dense row-major N x N, float32: F[p * n + q] = F_pq. A std::vector whose
// storage is a mapped file during an out-of-core bake (base/mapped_buffer.h).
struct FormFactorMatrix {
  std::size_t n = 0;
  MatrixValues values;
  // Entries whose estimate came out above 1 and were set to 1. F_pq is the
  // mean over P of the form factor from a point to Q, which is at most 1 at
  // every point, so an estimate above 1 is quadrature error (near surfaces,
  // where each receiver piece refines the source its own way) and 1 is closer
  // to the exact value. Reported in the manifest (checks.form_factors).
  std::size_t clamped_to_one = 0;
  // The patch areas A with which balance_form_factors made A F symmetric
  // (docs/method.md 5a); empty when F was not balanced (--closure-rays 0).
  // The transport's K = infinity solve uses them for its Cholesky
  // factorisation (transport/inverse_transport.h).
  std::vector<float> area;
  float operator()(std::size_t p, std::size_t q) const { return values[p * n + q]; }
};

FormFactorMatrix compute_form_factors(const Scene& scene, const RayTracer& tracer,
                                      const Voxelization& vox, const SampleSet& samples,
                                      const PatchSet& patches, const FormFactorSettings& settings,
                                      Progress* progress = nullptr);

// Only the rows settings deals to this process (row_offset, row_stride), in a
// compact buffer of about n^2 / row_stride values instead of the n x n matrix
// (core/distributed gathers them into the full matrix on the root). Own row
// p = row_at(k) is the segment values[first[k] .. first[k + 1]): F_pq for
// q = p .. n-1, then F_qp for q = p+1 .. n-1, every entry its pairs produce;
// the entries are bit-identical to the same entries of compute_form_factors.
struct FormFactorRows {
  std::size_t n = 0;
  std::size_t row_offset = 0;
  std::size_t row_stride = 1;
  std::vector<std::size_t> first;  // one more than the own rows
  std::vector<float> values;
  std::size_t clamped_to_one = 0;  // in these rows only
  std::size_t row_count() const { return first.empty() ? 0 : first.size() - 1; }
  std::size_t row_at(std::size_t k) const { return row_offset + k * row_stride; }
  static std::size_t segment_length(std::size_t n, std::size_t p);  // 2 (n - p) - 1
};

FormFactorRows compute_form_factor_rows(const Scene& scene, const RayTracer& tracer,
                                        const Voxelization& vox, const SampleSet& samples,
                                        const PatchSet& patches, const FormFactorSettings& settings,
                                        Progress* progress = nullptr);

// The checks every bake reports (energy, reciprocity, NaN/Inf).
struct FormFactorChecks {
  double row_sum_max = 0.0;
  double row_sum_mean = 0.0;
  std::size_t rows_above_one = 0;      // row sum > 1 + 1e-3
  double reciprocity_error_max = 0.0;  // max |A_i F_ij - A_j F_ji| / (A_i * max_j F_ij)
  double reciprocity_error_rel = 0.0;  // ||AF - (AF)^T||_F / ||AF||_F over the whole matrix
  std::size_t non_finite = 0;          // NaN or Inf entries
  std::size_t clamped_to_one = 0;      // FormFactorMatrix::clamped_to_one
  std::size_t patches_seeing_nothing = 0;
  double value_max = 0.0;
  // With the patches' closures (closure.h): rows above their closure by
  // more than float rounding (1e-5), and the largest excess.
  std::size_t rows_above_closure = 0;
  double closure_excess_max = 0.0;
};

FormFactorChecks check_form_factors(const FormFactorMatrix& f, const PatchSet& patches,
                                    const std::vector<float>* closure = nullptr);

// Drops the rows and columns of the patches with keep[p] == false.
FormFactorMatrix remove_patches(const FormFactorMatrix& f, const std::vector<bool>& keep);

}  // namespace bounce
