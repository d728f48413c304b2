#include "error_view.h"

#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QTableWidget>
#include <QVBoxLayout>

#include "compress/matrix_picture.h"
#include "error_histogram.h"

namespace bounce::views {

namespace {
constexpr int kMaxPictureSize = 4096;
}

ErrorView::ErrorView(QWidget* parent)
    : QWidget(parent),
      figures_(new QLabel(this)),
      element_(new MatrixPanel(this)),
      block_(new MatrixPanel(this)),
      histogram_(new ErrorHistogram(this)),
      table_(new QTableWidget(4, 4, this)),
      table_caption_(new QLabel(tr("Click a block of the right heatmap"), this)) {
  figures_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  figures_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  table_->setToolTip(tr("The block's 16 entries: exact -> decoded (mean of the stored channels)"));
  auto* heatmaps = new QHBoxLayout;
  heatmaps->addWidget(element_);
  heatmaps->addWidget(block_);
  auto* bottom = new QHBoxLayout;
  bottom->addWidget(histogram_, 1);
  auto* block_box = new QVBoxLayout;
  block_box->addWidget(table_caption_);
  block_box->addWidget(table_);
  bottom->addLayout(block_box, 1);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(figures_);
  layout->addLayout(heatmaps, 3);
  layout->addLayout(bottom, 2);
  connect(block_, &MatrixPanel::hovered, this,
          [this](std::size_t r0, std::size_t r1, std::size_t c0, std::size_t) {
            if (r0 != r1)
              block_->setToolTip(tr("block %1, %2: click for its values").arg(r0).arg(c0));
          });
  connect(block_, &MatrixPanel::clicked, this,
          [this](std::size_t r, std::size_t c) { select_block(r, c); });
}

void ErrorView::set_data(std::shared_ptr<const BakeViewData> bake) {
  data_ = std::move(bake);
  abs_error_.clear();
  exact_mean_.clear();
  decoded_mean_.clear();
  table_->clearContents();
  const LoadedBake* b = data_ ? &data_->bake : nullptr;
  if (!b || !b->compressed || b->dense.empty()) {
    const QString why = !b               ? tr("No bake loaded")
                        : !b->compressed ? tr("The matrix is stored dense: no compression error")
                                         : tr("No exact T.npy in this bake (bake with "
                                              "--dump-matrices, as the studio does)");
    figures_->setText(why);
    element_->clear_picture(why);
    block_->clear_picture(QString());
    histogram_->set_values({});
    return;
  }
  const CompressedMatrix& c = *b->compressed;
  const std::size_t n = b->size();
  std::vector<const float*> exact;
  for (const auto& m : b->dense) exact.push_back(m.data());
  // The core's own measurement, the one the bake put in its manifest.
  errors_ = measure_compression(exact, c, b->probe, &abs_error_);
  const MatrixError& e = errors_.matrix;
  figures_->setText(tr("%1 (%2, %3, kept %4): mean |error| %5, max %6, sum %7, relative "
                       "Frobenius %8, indirect light rel. RMS mean %9")
                        .arg(QString::fromStdString(c.codec), QString::fromStdString(c.encoder),
                             QString::fromStdString(c.ordering))
                        .arg(c.kept_fraction)
                        .arg(e.mean_abs, 0, 'g', 4)
                        .arg(e.max_abs, 0, 'g', 4)
                        .arg(e.sum_abs, 0, 'g', 4)
                        .arg(e.rel_frobenius, 0, 'g', 4)
                        .arg(errors_.indirect.rel_rms_mean, 0, 'g', 4));
  // Means over stored channels for the block table.
  exact_mean_.assign(n * n, 0.0f);
  decoded_mean_.assign(n * n, 0.0f);
  std::vector<float> decoded(n * n);
  const float scale = 1.0f / static_cast<float>(c.channels);
  for (int ch = 0; ch < c.channels; ++ch) {
    decompress_channel(c, ch, decoded.data());
    const std::vector<float>& t = b->dense[static_cast<std::size_t>(ch)];
    for (std::size_t k = 0; k < n * n; ++k) {
      exact_mean_[k] += t[k] * scale;
      decoded_mean_[k] += decoded[k] * scale;
    }
  }
  MatrixPictureSettings s;
  s.max_size = kMaxPictureSize;
  s.title = "|T~ - T| per entry, reordered (" + c.ordering + ")";
  element_->set_picture(matrix_picture(abs_error_.data(), n, s, &c.permutation),
                        MatrixPictureLayout::of(n, s.max_size, s.title));
  // Blocks live in the stored (reordered) matrix.
  std::vector<float> stored(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      stored[i * n + j] = abs_error_[c.permutation[i] * n + c.permutation[j]];
  std::size_t blocks = 0;
  const std::vector<float> sums = block_error_sums(stored.data(), n, blocks);
  s.title = "|T~ - T| per 4x4 block of T.dds";
  block_->set_picture(matrix_picture(sums.data(), blocks, s),
                      MatrixPictureLayout::of(blocks, s.max_size, s.title));
  histogram_->set_values(abs_error_);
  element_->fit();
  block_->fit();
}

void ErrorView::select_block(std::size_t block_row, std::size_t block_col) {
  if (!has_errors()) return;
  const CompressedMatrix& c = *data_->bake.compressed;
  const std::size_t n = data_->patch_count();
  table_caption_->setText(tr("Block %1, %2 (stored rows %3..%4, columns %5..%6): exact -> decoded")
                              .arg(block_row)
                              .arg(block_col)
                              .arg(4 * block_row)
                              .arg(4 * block_row + 3)
                              .arg(4 * block_col)
                              .arg(4 * block_col + 3));
  for (int r = 0; r < 4; ++r)
    for (int col = 0; col < 4; ++col) {
      const std::size_t i = 4 * block_row + static_cast<std::size_t>(r);
      const std::size_t j = 4 * block_col + static_cast<std::size_t>(col);
      QString text = tr("padding");
      if (i < n && j < n) {
        const std::size_t k = c.permutation[i] * n + c.permutation[j];
        text = QString("%1 -> %2")
                   .arg(static_cast<double>(exact_mean_[k]), 0, 'g', 4)
                   .arg(static_cast<double>(decoded_mean_[k]), 0, 'g', 4);
      }
      table_->setItem(r, col, new QTableWidgetItem(text));
    }
}

QString ErrorView::block_cell(int r, int c) const {
  const QTableWidgetItem* item = table_->item(r, c);
  return item ? item->text() : QString();
}

}  // namespace bounce::views
