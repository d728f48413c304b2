#pragma once
// Temporal radiosity with importance on the light, read from the compressed
// matrix the runtime holds. A frame estimates the indirect light T~ b of
// first-hit light b without the full product: it picks S block columns
// (4 stored columns each) by systematic sampling (dynamic/systematic_draw.h)
// with probability proportional to
//   m_J = sum over columns q of J and colours k of c_qk |b_qk|,
// c_qk = sum_p |T~_pq| (the column's whole reach, computed once), and
// multiplies exactly those block columns, scaled by 1 / (S m_J / sum m), as
// a product over the whole column (dynamic/compressed_columns.h). Every
// patch shares the frame's columns, like S virtual lights placed where the
// light does most. Unbiased: each column's expected weight is 1, and a
// block column of zero mass contributes 0 to T~ b. Columns of unlit
// patches are never read; those carrying more than 1/S of the mass are read
// every frame (no noise from them). Successive frames shift the systematic
// offset by the golden ratio (stratify_frames), so f frames of a steady
// light cover the mass like f * S stratified draws, not f independent sets;
// each frame's offset is still uniform, so each frame stays unbiased.
//
// The frames are blended into a history whose length adapts to the light
// (dynamic/adaptive_history.h): the change of b is measured as
//   change = sum_qk c_qk |b_qk - b'_qk| / sum_qk c_qk |b_qk|,
// an upper bound of ||T~ (b - b')||_1 / ||T~ b||_1 for T~ >= 0 (the column
// sums bound the L1 norm of T~), and shortens the running mean by it.
//
// Cost per frame: O(n) to gather b and the masses, then S block columns
// times nb block rows of 8-byte blocks and the kept entries of those
// columns: about S / nb of the product's block reads, each block column one
// sequential run. Memory: the palettes are the caller's (shared with the
// runtime's product); this object holds the blocks and the kept entries by
// column (as large as the tables' by-row ones, which it does not read) and
// O(n) buffers.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "compress/compressed_transport_tables.h"
#include "dynamic/adaptive_history.h"
#include "dynamic/compressed_columns.h"
#include "dynamic/systematic_draw.h"

namespace bounce {

struct LightTemporalSettings {
  int block_columns = 12;  // S, draws per frame (a block column may be drawn more than once)
  AdaptiveHistorySettings history;
  bool stratify_frames = true;  // golden-ratio offsets; false: independent frames
  std::uint32_t seed = 1;
};

class LightTemporalRadiosity {
 public:
  // Keeps a reference to `tables` (they must outlive this object). Throws
  // bounce::Error for S < 1, max_frames < 0 or change_scale <= 0.
  LightTemporalRadiosity(const CompressedTransportTables& tables,
                         const LightTemporalSettings& settings);

  // One frame's estimate of T~ b (no history), with the offset of `frame`.
  // b, out: one entry per patch (bounce::Error otherwise).
  void estimate(std::span<const glm::vec3> b, std::uint32_t frame, std::span<glm::vec3> out);

  // The change of b against the light of the previous step (0 before the
  // first step; infinite from darkness to light).
  double light_change(std::span<const glm::vec3> b) const;

  // One frame: shorten the history by the light's change, estimate, blend
  // into `history` (one entry per patch, in place), advance.
  void step(std::span<const glm::vec3> b, std::span<glm::vec3> history);
  // Forget the history (the next step replaces it).
  void reset();

  double history_frames() const { return history_frames_; }  // k before the next step
  double last_change() const { return last_change_; }
  float last_weight() const { return last_weight_; }  // the history's weight in the last step
  std::size_t size() const { return tables_.n; }
  const LightTemporalSettings& settings() const { return settings_; }
  // The block columns and kept entries the last estimate read.
  std::size_t last_block_columns() const { return draw_.items.size(); }
  std::size_t last_kept_entries() const { return last_kept_; }
  // Bytes the last estimate read from the tables and b (blocks, kept
  // entries with their column indices, b and the column sums).
  std::size_t last_bytes_read() const;
  // This object's own buffers (not the shared tables, not the history),
  // the by-column kept entries included.
  std::size_t own_bytes() const;
  // What it reads of the shared tables: the palettes (the blocks and kept
  // entries it reads from its own by-column copies).
  std::size_t table_bytes_read() const;

 private:
  const CompressedTransportTables& tables_;
  LightTemporalSettings settings_;
  std::vector<std::uint8_t> column_blocks_;  // blocks_by_column(tables_)
  KeptColumns kept_;
  std::vector<float> column_sums_;  // 3 per stored column
  std::vector<float> b_stored_;     // 4 per stored column, padded
  std::vector<float> scaled_;       // b_stored_ of the drawn block columns, scaled
  std::vector<float> previous_;     // b_stored_ of the previous step
  std::vector<double> mass_;        // per block column
  std::vector<float> y_stored_;     // 4 per stored row (R, G, B, 0)
  SystematicDraw draw_;
  std::size_t last_kept_ = 0;
  bool has_previous_ = false;
  double history_frames_ = 0.0;
  double last_change_ = 0.0;
  float last_weight_ = 0.0f;
  std::uint32_t frame_ = 0;
  double offset0_ = 0.0;

  // The estimate into y_stored_ (stored order), b left in b_stored_; with
  // `measure_change`, last_change_ = the change of b against previous_.
  void estimate_stored(std::span<const glm::vec3> b, std::uint32_t frame, bool measure_change);
};

}  // namespace bounce
