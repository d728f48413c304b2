#include "matrix_view.h"

#include <algorithm>

#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>

#include "bounce/compression.h"

namespace bounce::views {

namespace {

// Large enough to see single entries of the bakes people tune (N ~ 4000);
// beyond it a pixel shows the maximum of its block of entries.
constexpr int kMaxPictureSize = 4096;

}  // namespace

MatrixView::MatrixView(QWidget* parent)
    : QWidget(parent),
      channel_box_(new QComboBox(this)),
      source_(new QLabel(this)),
      hover_(new QLabel(this)),
      before_(new MatrixPanel(this)),
      after_(new MatrixPanel(this)),
      mark_(new QLabel(this)),
      back_(new QPushButton(tr("Show patch in the patch view"), this)) {
  channel_box_->addItems({tr("Mean of channels"), tr("Red"), tr("Green"), tr("Blue")});
  channel_box_->setToolTip(tr("Which colour channel's matrix T_c to show"));
  auto* fit_button = new QPushButton(tr("Fit"), this);
  auto* one_button = new QPushButton(tr("1:1"), this);
  // The controls never force a minimum width on the view: at small sizes
  // (screenshots) they are cut off instead.
  auto* bar = new QWidget(this);
  bar->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
  auto* controls = new QHBoxLayout(bar);
  controls->setContentsMargins(0, 0, 0, 0);
  controls->addWidget(new QLabel(tr("Channel"), this));
  controls->addWidget(channel_box_);
  controls->addWidget(fit_button);
  controls->addWidget(one_button);
  controls->addWidget(source_, 1);
  auto* panels = new QHBoxLayout;
  panels->addWidget(before_);
  panels->addWidget(after_);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(bar);
  layout->addLayout(panels, 1);
  layout->addWidget(hover_);
  auto* mark_bar = new QWidget(this);
  mark_bar->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
  auto* mark_layout = new QHBoxLayout(mark_bar);
  mark_layout->setContentsMargins(0, 0, 0, 0);
  mark_layout->addWidget(mark_, 1);
  mark_layout->addWidget(back_);
  layout->addWidget(mark_bar);
  hover_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  mark_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  back_->setEnabled(false);
  back_->setToolTip(
      tr("Pick the marked row's patch in the patch view (click an entry to mark "
         "its row)"));
  connect(back_, &QPushButton::clicked, this, [this] {
    if (marked_patch_ >= 0) emit patch_requested(marked_patch_);
  });
  connect(before_, &MatrixPanel::clicked, this,
          [this](std::size_t r, std::size_t c) { pick_entry(false, r, c); });
  connect(after_, &MatrixPanel::clicked, this,
          [this](std::size_t r, std::size_t c) { pick_entry(true, r, c); });
  before_->mirror(after_);
  after_->mirror(before_);
  connect(channel_box_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int) { rebuild(); });
  connect(fit_button, &QPushButton::clicked, this, &MatrixView::fit);
  connect(one_button, &QPushButton::clicked, this, [this] { before_->set_zoom(1.0); });
  connect(before_, &MatrixPanel::hovered, this,
          [this](std::size_t r0, std::size_t r1, std::size_t c0, std::size_t c1) {
            show_hover(false, r0, r1, c0, c1);
          });
  connect(after_, &MatrixPanel::hovered, this,
          [this](std::size_t r0, std::size_t r1, std::size_t c0, std::size_t c1) {
            show_hover(true, r0, r1, c0, c1);
          });
}

void MatrixView::set_data(std::shared_ptr<const BakeViewData> bake) {
  data_ = std::move(bake);
  marked_patch_ = -1;
  rebuild();
  fit();
}

void MatrixView::set_channel(Channel channel) {
  channel_box_->setCurrentIndex(static_cast<int>(channel));
}

QString MatrixView::hover_text() const { return hover_->text(); }

void MatrixView::fit() {
  before_->fit();
  after_->fit();
}

void MatrixView::rebuild() {
  shown_.clear();
  hover_->clear();
  if (!data_ || data_->patch_count() == 0) {
    before_->clear_picture(tr("No bake loaded"));
    after_->clear_picture(QString());
    source_->clear();
    return;
  }
  const LoadedBake& b = data_->bake;
  const std::size_t n = b.size();
  const int stored = b.stored_channels;
  // The exact matrices when the bake kept them (T.npy), else the decoded ones.
  exact_ = !b.dense.empty();
  std::vector<std::vector<float>> decoded;
  if (!exact_) {
    decoded.assign(static_cast<std::size_t>(stored), std::vector<float>(n * n));
    for (int c = 0; c < stored; ++c)
      decompress_channel(*b.compressed, c, decoded[static_cast<std::size_t>(c)].data());
  }
  const auto& channels = exact_ ? b.dense : decoded;
  const int choice = channel_box_->currentIndex();
  if (choice == static_cast<int>(Channel::Mean)) {
    // The same mean of the stored channels as the bake's T.png.
    shown_.assign(n * n, 0.0f);
    const float scale = 1.0f / static_cast<float>(channels.size());
    for (const auto& c : channels)
      for (std::size_t k = 0; k < n * n; ++k) shown_[k] += c[k] * scale;
  } else {
    shown_ =
        channels[static_cast<std::size_t>(b.channel_of_rgb[static_cast<std::size_t>(choice - 1)])];
  }
  // Captions as in the bake folder's T.png / T_reordered.png (core/bake/bake_pictures.cpp).
  const std::string what = choice != static_cast<int>(Channel::Mean)
                               ? "T_" + channel_box_->currentText().left(1).toStdString()
                           : channels.size() == 1 ? "T"
                                                  : "T (mean of the stored channels)";
  MatrixPictureSettings settings;
  settings.max_size = kMaxPictureSize;
  settings.title = what + ", patch order, " + std::to_string(n) + " x " + std::to_string(n);
  before_->set_picture(matrix_picture(shown_.data(), n, settings),
                       MatrixPictureLayout::of(n, settings.max_size, settings.title));
  if (b.compressed) {
    settings.title = what + ", reordered (" + b.compressed->ordering + ")";
    after_->set_picture(matrix_picture(shown_.data(), n, settings, &b.compressed->permutation),
                        MatrixPictureLayout::of(n, settings.max_size, settings.title));
  } else {
    after_->clear_picture(tr("Stored dense (exact): no reordering"));
  }
  source_->setText(exact_ ? tr("exact T (T.npy)")
                          : tr("T decoded from T.dds + kept entries (no T.npy in this bake)"));
  restore_mark();
}

void MatrixView::mark_row(int patch, std::size_t stored_row, std::size_t stored_col_first,
                          std::size_t stored_col_last) {
  const std::size_t n = data_ ? data_->patch_count() : 0;
  marked_patch_ = patch >= 0 && static_cast<std::size_t>(patch) < n ? patch : -1;
  marked_row_ = stored_row;
  marked_col_first_ = std::min(stored_col_first, n);
  marked_col_last_ = std::min(stored_col_last, n);
  restore_mark();
}

QString MatrixView::mark_text() const { return mark_->text(); }

void MatrixView::restore_mark() {
  back_->setEnabled(marked_patch_ >= 0);
  if (marked_patch_ < 0 || !data_) {
    before_->set_highlights({}, false);
    after_->set_highlights({}, false);
    mark_->clear();
    return;
  }
  const std::size_t n = data_->patch_count(), p = static_cast<std::size_t>(marked_patch_);
  const CompressedMatrix* c = data_->bake.compressed ? &*data_->bake.compressed : nullptr;
  // Patch order: the whole row, and the block's entries where the
  // permutation scattered them.
  std::vector<EntryRect> before{{p, p + 1, 0, n}};
  QString patches;
  if (c)
    for (std::size_t k = marked_col_first_; k < marked_col_last_; ++k) {
      const std::size_t j = c->permutation[k];
      before.push_back({p, p + 1, j, j + 1});
      patches += (patches.isEmpty() ? "" : ", ") + QString::number(j);
    }
  before_->set_highlights(before, !c);
  QString text = tr("Marked: row of patch %1").arg(marked_patch_);
  if (c && marked_row_ < n && c->permutation[marked_row_] == p) {
    std::vector<EntryRect> after{{marked_row_, marked_row_ + 1, 0, n}};
    text += tr(" (stored row %1)").arg(marked_row_);
    if (marked_col_first_ < marked_col_last_) {
      const std::size_t top = marked_row_ / 4 * 4;
      after.insert(after.begin(), {top, std::min(top + 4, n), marked_col_first_, marked_col_last_});
      text += tr(", block %1, %2: stored columns %3..%4 = patches %5")
                  .arg(marked_row_ / 4)
                  .arg(marked_col_first_ / 4)
                  .arg(marked_col_first_)
                  .arg(marked_col_last_ - 1)
                  .arg(patches);
    }
    after_->set_highlights(after, true);
  } else {
    after_->set_highlights({}, false);
  }
  mark_->setText(text);
}

void MatrixView::pick_entry(bool after, std::size_t row, std::size_t col) {
  if (!data_) return;
  const CompressedMatrix* c = data_->bake.compressed ? &*data_->bake.compressed : nullptr;
  if (!c) {
    mark_row(static_cast<int>(row));
    return;
  }
  // Stored (reordered) row and column of the entry, and the patch of its row.
  std::size_t stored_row = row, stored_col = col;
  if (!after) {
    const auto& perm = c->permutation;
    stored_row = static_cast<std::size_t>(std::find(perm.begin(), perm.end(), row) - perm.begin());
    stored_col = static_cast<std::size_t>(std::find(perm.begin(), perm.end(), col) - perm.begin());
  }
  const std::size_t first = stored_col / 4 * 4;
  mark_row(static_cast<int>(c->permutation[stored_row]), stored_row, first,
           std::min(first + 4, data_->patch_count()));
}

float MatrixView::value(std::size_t row, std::size_t col) const {
  return shown_[row * data_->patch_count() + col];
}

void MatrixView::show_hover(bool after, std::size_t r0, std::size_t r1, std::size_t c0,
                            std::size_t c1) {
  if (r0 == r1 || !data_) {
    hover_->clear();
    return;
  }
  const LoadedBake& b = data_->bake;
  auto patch = [&](std::size_t k) {
    return after && b.compressed ? static_cast<std::size_t>(b.compressed->permutation[k]) : k;
  };
  if (r1 - r0 == 1 && c1 - c0 == 1) {
    const std::size_t pi = patch(r0), pj = patch(c0);
    hover_->setText(tr("i = %1, j = %2   patches %3 -> %4   T = %5")
                        .arg(r0)
                        .arg(c0)
                        .arg(pi)
                        .arg(pj)
                        .arg(static_cast<double>(value(pi, pj)), 0, 'g', 6));
    return;
  }
  // A downsampled pixel: the largest |entry| of its block, as drawn.
  float m = 0.0f;
  for (std::size_t i = r0; i < r1; ++i)
    for (std::size_t j = c0; j < c1; ++j) m = std::max(m, std::abs(value(patch(i), patch(j))));
  hover_->setText(tr("i = %1..%2, j = %3..%4   max |T| = %5")
                      .arg(r0)
                      .arg(r1 - 1)
                      .arg(c0)
                      .arg(c1 - 1)
                      .arg(static_cast<double>(m), 0, 'g', 6));
}

}  // namespace bounce::views
