#pragma once
// View 4: compression error. |T~ - T| per entry (sum over stored channels)
// and per 4x4 block of the stored (reordered) matrix as heatmaps, a
// histogram of the per-entry error, the matrix error figures (mean, max and
// sum of |error|, measured by the core's measure_compression against T.npy),
// and the 16 values of a clicked block before (exact) and after (decoded)
// compression.
// A codec and ordering switch re-compresses the bake's exact T.npy with the
// core's compression stage (store_matrices, at the bake's kept fraction), so
// codecs can be compared on the same matrix. The measuring, re-compressing
// and the pictures are the core's (compression_error_maps), run on the
// studio's view jobs; the view shows their results.
#include <map>
#include <memory>
#include <optional>

#include <QWidget>

#include "bake_view_data.h"
#include "bounce/compression.h"
#include "matrix_panel.h"

class QComboBox;
class QLabel;
class QTableWidget;

namespace bounce::views {

class ErrorHistogram;
class ViewJobs;

class ErrorView : public QWidget {
  Q_OBJECT
 public:
  explicit ErrorView(ViewJobs& jobs, QWidget* parent = nullptr);
  ~ErrorView() override;

  // Measures the bake's own compressed matrix on the jobs: has_errors()
  // once it is shown.
  void set_data(std::shared_ptr<const BakeViewData> bake);
  // The figures shown (valid when has_errors()).
  const CompressionErrors& errors() const { return errors_; }
  bool has_errors() const { return shown_ != nullptr; }
  // The compressed matrix shown: the bake's own, or a comparison's.
  const CompressedMatrix* shown_matrix() const { return shown_; }
  // Shows the matrix re-compressed with `codec` (Paper or Ours; unset: the
  // bake's own stored matrix) and `ordering` (unset: the codec's own), at the
  // bake's kept fraction. Runs on the jobs the first time; emits
  // comparison_ready once shown (at once when cached or the bake's own,
  // measured).
  void compare(std::optional<CodecChoice> codec, std::optional<OrderingMethod> ordering);
  bool comparing() const { return comparing_; }
  // Shows block (block_row, block_col) of the stored matrix in the table.
  void select_block(std::size_t block_row, std::size_t block_col);
  // Cell text of the table: row r (0..3) and column c (0..3) of the block,
  // "exact -> decoded" of the mean over stored channels.
  QString block_cell(int r, int c) const;
  QString figures_text() const;
  MatrixPanel* element_panel() const { return element_; }
  MatrixPanel* block_panel() const { return block_; }
  QComboBox* codec_box() const { return codec_box_; }
  QComboBox* ordering_box() const { return ordering_box_; }

 signals:
  void comparison_ready();
  void comparison_failed(const QString& message);

 private:
  using Key = std::pair<int, int>;  // codec, ordering (-1: unset)
  // A compressed matrix with its error maps: the bake's own (no storage) or
  // a re-compression's.
  struct Shown {
    std::shared_ptr<const MatrixStorage> storage;
    CompressionErrorMaps maps;
  };
  // The one job of this view: what is to be shown next.
  static constexpr int kShowJob = 0;

  // Measures the bake's own matrix on the jobs and shows it; emits
  // comparison_ready when `ready`.
  void measure_own(bool ready);
  void show_matrix(std::shared_ptr<const Shown> shown, const QString& source);
  void compare_from_boxes();

  ViewJobs& jobs_;
  std::shared_ptr<const BakeViewData> data_;
  CompressionErrors errors_;
  const CompressedMatrix* shown_ = nullptr;
  std::shared_ptr<const Shown> shown_data_;  // keeps shown_ and its maps
  std::shared_ptr<const Shown> own_;         // the bake's own matrix, once measured
  std::map<Key, std::shared_ptr<const Shown>> comparisons_;
  bool comparing_ = false;
  QComboBox* codec_box_;
  QComboBox* ordering_box_;
  QLabel* figures_;
  MatrixPanel* element_;
  MatrixPanel* block_;
  ErrorHistogram* histogram_;
  QTableWidget* table_;
  QLabel* table_caption_;
};

}  // namespace bounce::views
