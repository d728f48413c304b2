#pragma once
// View 4: compression error. |T~ - T| per entry (sum over stored channels)
// and per 4x4 block of the stored (reordered) matrix as heatmaps, a
// histogram of the per-entry error, the matrix error figures of paper 000
// (measured by the core's measure_compression against T.npy), and the 16
// values of a clicked block before (exact) and after (decoded) compression.
#include <memory>

#include <QWidget>

#include "bake_view_data.h"
#include "compress/compression_error.h"
#include "matrix_panel.h"

class QLabel;
class QTableWidget;

namespace bounce::views {

class ErrorHistogram;

class ErrorView : public QWidget {
  Q_OBJECT
 public:
  explicit ErrorView(QWidget* parent = nullptr);

  void set_data(std::shared_ptr<const BakeViewData> bake);
  // The figures shown (valid when has_errors()).
  const CompressionErrors& errors() const { return errors_; }
  bool has_errors() const { return !abs_error_.empty(); }
  // Shows block (block_row, block_col) of the stored matrix in the table.
  void select_block(std::size_t block_row, std::size_t block_col);
  // Cell text of the table: row r (0..3) and column c (0..3) of the block,
  // "exact -> decoded" of the mean over stored channels.
  QString block_cell(int r, int c) const;
  MatrixPanel* element_panel() const { return element_; }
  MatrixPanel* block_panel() const { return block_; }

 private:
  std::shared_ptr<const BakeViewData> data_;
  CompressionErrors errors_;
  std::vector<float> abs_error_;  // patch order
  std::vector<float> exact_mean_, decoded_mean_;
  QLabel* figures_;
  MatrixPanel* element_;
  MatrixPanel* block_;
  ErrorHistogram* histogram_;
  QTableWidget* table_;
  QLabel* table_caption_;
};

}  // namespace bounce::views
