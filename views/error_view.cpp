#include "error_view.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QTableWidget>
#include <QVBoxLayout>

#include "bounce/compression.h"
#include "bounce/diagnostics.h"
#include "bounce/error.h"
#include "error_histogram.h"
#include "view_jobs.h"

namespace bounce::views {

namespace {
constexpr int kMaxPictureSize = 4096;
constexpr int kUnset = -1;  // combo data: the bake's codec / the codec's own ordering
}  // namespace

ErrorView::ErrorView(ViewJobs& jobs, QWidget* parent)
    : QWidget(parent),
      jobs_(jobs),
      codec_box_(new QComboBox(this)),
      ordering_box_(new QComboBox(this)),
      figures_(new QLabel(this)),
      element_(new MatrixPanel(this)),
      block_(new MatrixPanel(this)),
      histogram_(new ErrorHistogram(this)),
      table_(new QTableWidget(4, 4, this)),
      table_caption_(new QLabel(tr("Click a block of the right heatmap"), this)) {
  codec_box_->addItem(tr("as baked"), kUnset);
  codec_box_->addItem(tr("paper (published BC1)"), static_cast<int>(CodecChoice::LargestEntries));
  codec_box_->addItem(tr("ours"), static_cast<int>(CodecChoice::LightWeighted));
  codec_box_->setToolTip(
      tr("Compare codecs on this bake: re-compresses its "
         "exact matrix (T.npy) with the bake's "
         "compression stage at the bake's kept fraction, in "
         "the background. 'as baked' shows "
         "the stored T.dds"));
  ordering_box_->addItem(tr("codec's own"), kUnset);
  for (OrderingMethod m : {OrderingMethod::None, OrderingMethod::GreedyRowTour,
                           OrderingMethod::GreedyRowThenColumnTour, OrderingMethod::SketchTour})
    ordering_box_->addItem(QString::fromUtf8(ordering_name(m)), static_cast<int>(m));
  ordering_box_->setToolTip(
      tr("Row/column ordering of the comparison: which "
         "rows share a 4x4 block. The paper's "
         "tour is slow on large matrices"));
  // Narrow windows (small screenshots) must not be widened by the menus.
  for (QComboBox* box : {codec_box_, ordering_box_}) {
    box->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    box->setMinimumContentsLength(8);
  }
  figures_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  figures_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  table_->setToolTip(
      tr("The block's 16 entries: exact -> decoded (mean of the "
         "stored channels)"));
  auto* switches = new QHBoxLayout;
  switches->addWidget(new QLabel(tr("Codec"), this));
  switches->addWidget(codec_box_);
  switches->addWidget(new QLabel(tr("Ordering"), this));
  switches->addWidget(ordering_box_);
  switches->addStretch(1);
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
  layout->addLayout(switches);
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
  for (QComboBox* box : {codec_box_, ordering_box_})
    connect(box, qOverload<int>(&QComboBox::currentIndexChanged), this,
            [this](int) { compare_from_boxes(); });
}

ErrorView::~ErrorView() = default;

void ErrorView::set_data(std::shared_ptr<const BakeViewData> bake) {
  jobs_.forget(this);
  comparing_ = false;
  data_ = std::move(bake);
  shown_ = nullptr;
  shown_data_.reset();
  own_.reset();
  comparisons_.clear();
  table_->clearContents();
  for (QComboBox* box : {codec_box_, ordering_box_}) {
    const QSignalBlocker quiet(box);
    box->setCurrentIndex(0);
  }
  const LoadedBake* b = data_ ? &data_->bake : nullptr;
  const bool usable = b && b->compressed && !b->dense.empty();
  codec_box_->setEnabled(usable);
  ordering_box_->setEnabled(usable);
  if (!usable) {
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
  measure_own(false);
}

void ErrorView::measure_own(bool ready) {
  figures_->setText(tr("Measuring the compression error..."));
  comparing_ = true;
  auto bake = data_;
  jobs_.run<std::shared_ptr<const Shown>>(
      this, kShowJob,
      [bake](const ViewJobs::KeepGoing&) {
        const LoadedBake& b = bake->bake;
        std::vector<const float*> exact;
        for (const auto& m : b.dense) exact.push_back(m.data());
        // The core's own measurement, the one the bake put in its manifest.
        std::vector<float> abs_error;
        const CompressionErrors errors =
            measure_compression(exact, *b.compressed, b.probe, &abs_error);
        return std::make_shared<const Shown>(
            Shown{nullptr, compression_error_maps(exact, b.size(), *b.compressed, errors,
                                                  std::move(abs_error), kMaxPictureSize)});
      },
      [this, ready](std::shared_ptr<const Shown> own) {
        comparing_ = false;
        own_ = own;
        show_matrix(std::move(own), tr("as baked"));
        if (ready) emit comparison_ready();
      },
      [this](const QString& message) {
        comparing_ = false;
        figures_->setText(tr("Measuring the compression error failed: %1").arg(message));
        emit comparison_failed(message);
      });
}

void ErrorView::compare_from_boxes() {
  const int codec = codec_box_->currentData().toInt();
  const int ordering = ordering_box_->currentData().toInt();
  compare(codec == kUnset ? std::nullopt : std::optional(static_cast<CodecChoice>(codec)),
          ordering == kUnset ? std::nullopt : std::optional(static_cast<OrderingMethod>(ordering)));
}

void ErrorView::compare(std::optional<CodecChoice> codec, std::optional<OrderingMethod> ordering) {
  if (!data_ || !data_->bake.compressed || data_->bake.dense.empty()) {
    emit comparison_failed(tr("nothing to compare: the bake has no compressed matrix and T.npy"));
    return;
  }
  // The menus show the choice also when it comes from code (headless, tests).
  for (auto [box, value] :
       {std::pair{codec_box_, codec ? static_cast<int>(*codec) : kUnset},
        std::pair{ordering_box_, ordering ? static_cast<int>(*ordering) : kUnset}}) {
    const QSignalBlocker quiet(box);
    box->setCurrentIndex(box->findData(value));
  }
  // A newer choice replaces one still being computed.
  jobs_.forget(this);
  comparing_ = false;
  const CompressedMatrix& own = *data_->bake.compressed;
  if (!codec && !ordering) {
    if (!own_) {
      measure_own(true);
      return;
    }
    show_matrix(own_, tr("as baked"));
    emit comparison_ready();
    return;
  }
  BakeSettings s;
  s.codec = codec.value_or(own.codec == "paper" ? CodecChoice::LargestEntries
                                                : CodecChoice::LightWeighted);
  s.kept_fraction = own.kept_fraction;  // compare at the bake's share of exact entries
  s.ordering = ordering;
  s.pictures = false;
  const Key key{static_cast<int>(s.codec), ordering ? static_cast<int>(*ordering) : kUnset};
  const QString source = tr("re-compressed from T.npy");
  if (const auto it = comparisons_.find(key); it != comparisons_.end()) {
    show_matrix(it->second, source);
    emit comparison_ready();
    return;
  }
  figures_->setText(
      tr("Re-compressing with %1 (ordering %2)...")
          .arg(QString::fromUtf8(to_string(s.codec)),
               ordering ? QString::fromUtf8(ordering_name(*ordering)) : tr("the codec's own")));
  comparing_ = true;
  auto bake = data_;
  jobs_.run<std::shared_ptr<const Shown>>(
      this, kShowJob,
      [bake, s](const ViewJobs::KeepGoing& keep_going) {
        Progress progress([&keep_going](const std::string&, double) { return keep_going(); });
        Diagnostics diagnostics;
        const LoadedBake& b = bake->bake;
        std::vector<const float*> exact;
        for (const auto& m : b.dense) exact.push_back(m.data());
        auto storage = std::make_shared<const MatrixStorage>(
            store_matrices(exact, b.size(), b.probe, s, &progress, diagnostics));
        if (!storage->compressed) throw Error("re-compression", "no compressed matrix came out");
        CompressionErrorMaps maps =
            compression_error_maps(exact, b.size(), *storage->compressed, storage->errors,
                                   storage->abs_error_sum, kMaxPictureSize);
        return std::make_shared<const Shown>(Shown{std::move(storage), std::move(maps)});
      },
      [this, key, source](std::shared_ptr<const Shown> shown) {
        comparing_ = false;
        comparisons_[key] = shown;
        show_matrix(std::move(shown), source);
        emit comparison_ready();
      },
      [this](const QString& message) {
        comparing_ = false;
        figures_->setText(tr("Re-compression failed: %1").arg(message));
        emit comparison_failed(message);
      });
}

QString ErrorView::figures_text() const { return figures_->text(); }

void ErrorView::show_matrix(std::shared_ptr<const Shown> shown, const QString& source) {
  const std::size_t n = data_->bake.size();
  shown_data_ = std::move(shown);
  const CompressedMatrix& c =
      shown_data_->storage ? *shown_data_->storage->compressed : *data_->bake.compressed;
  const CompressionErrorMaps& maps = shown_data_->maps;
  shown_ = &c;
  errors_ = maps.errors;
  table_->clearContents();
  table_caption_->setText(tr("Click a block of the right heatmap"));
  const MatrixError& e = errors_.matrix;
  figures_->setText(tr("%1, %2 (%3, %4, kept %5): mean |error| %6, max %7, sum %8, relative "
                       "Frobenius %9, indirect light rel. RMS mean %10")
                        .arg(source, QString::fromStdString(c.codec),
                             QString::fromStdString(c.encoder), QString::fromStdString(c.ordering))
                        .arg(c.kept_fraction)
                        .arg(e.mean_abs, 0, 'g', 4)
                        .arg(e.max_abs, 0, 'g', 4)
                        .arg(e.sum_abs, 0, 'g', 4)
                        .arg(e.rel_frobenius, 0, 'g', 4)
                        .arg(errors_.indirect.rel_rms_mean, 0, 'g', 4));
  element_->set_picture(maps.entry_picture,
                        MatrixPictureLayout::of(n, kMaxPictureSize, maps.entry_title));
  block_->set_picture(maps.block_picture,
                      MatrixPictureLayout::of(maps.blocks, kMaxPictureSize, maps.block_title));
  histogram_->set_values(maps.abs_error);
  element_->fit();
  block_->fit();
}

void ErrorView::select_block(std::size_t block_row, std::size_t block_col) {
  if (!has_errors()) return;
  const CompressedMatrix& c = *shown_;
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
                   .arg(static_cast<double>(shown_data_->maps.exact_mean[k]), 0, 'g', 4)
                   .arg(static_cast<double>(shown_data_->maps.decoded_mean[k]), 0, 'g', 4);
      }
      table_->setItem(r, col, new QTableWidgetItem(text));
    }
}

QString ErrorView::block_cell(int r, int c) const {
  const QTableWidgetItem* item = table_->item(r, c);
  return item ? item->text() : QString();
}

}  // namespace bounce::views
