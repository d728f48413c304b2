#include "preview_view.h"

#include <QCheckBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QVBoxLayout>

#include "preview_widget.h"

namespace bounce::views {

PreviewView::PreviewView(ViewJobs& jobs, QWidget* parent)
    : QWidget(parent),
      preview_(new PreviewWidget(jobs, this)),
      direct_(new QCheckBox(tr("Direct"), this)),
      indirect_(new QCheckBox(tr("Indirect"), this)),
      ao_(new QCheckBox(tr("Ambient occlusion"), this)),
      normal_maps_(new QCheckBox(tr("Normal maps"), this)),
      status_(new QLabel(this)) {
  direct_->setToolTip(tr("Light straight from the light, shadowed by the shadow map (PCF)"));
  indirect_->setToolTip(
      tr("Light after one or more bounces: the bake's matrix times the direct light on the "
         "patches, solved again whenever the light moves"));
  ao_->setToolTip(tr("Screen-space ambient occlusion (32 samples, blurred) on the indirect light"));
  normal_maps_->setToolTip(
      tr("Shade with the materials' normal maps (the bake lights the flat surface)"));
  for (QCheckBox* box : {direct_, indirect_, ao_, normal_maps_}) {
    box->setChecked(true);
    connect(box, &QCheckBox::toggled, this, &PreviewView::apply_switches);
  }
  status_->setText(
      tr("Drag: orbit. Right drag or wheel: zoom. Ctrl + drag: move the light "
         "(Ctrl + wheel: nearer or farther)."));
  auto* row = new QHBoxLayout;
  row->addWidget(direct_);
  row->addWidget(indirect_);
  row->addWidget(ao_);
  row->addWidget(normal_maps_);
  row->addSpacing(16);
  row->addWidget(status_, 1);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addLayout(row);
  layout->addWidget(preview_, 1);
}

void PreviewView::apply_switches() {
  PreviewWidget::Passes p;
  p.direct = direct_->isChecked();
  p.indirect = indirect_->isChecked();
  p.ao = ao_->isChecked();
  p.normal_maps = normal_maps_->isChecked();
  ao_->setEnabled(p.indirect);  // the occlusion darkens the indirect light only
  preview_->set_passes(p);
}

void PreviewView::set_data(std::shared_ptr<const BakeViewData> bake) {
  try {
    preview_->set_data(std::move(bake));
    status_->setText(
        tr("Drag: orbit. Right drag or wheel: zoom. Ctrl + drag: move the light "
           "(Ctrl + wheel: nearer or farther)."));
  } catch (const std::exception& e) {
    preview_->clear();
    status_->setText(tr("No preview: %1").arg(QString::fromStdString(e.what())));
  }
}

}  // namespace bounce::views
