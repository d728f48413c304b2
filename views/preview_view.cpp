#include "preview_view.h"

#include <exception>
#include <initializer_list>

#include <QCheckBox>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
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
      probes_(new QCheckBox(tr("Light probes"), this)),
      sphere_(new QCheckBox(tr("Probe-lit object"), this)),
      load_object_(new QPushButton(tr("Object…"), this)),
      status_(new QLabel(this)) {
  direct_->setToolTip(tr("Light straight from the light, shadowed by the shadow map (PCF)"));
  indirect_->setToolTip(
      tr("Light after one or more bounces: the bake's matrix times the direct light on the "
         "patches, solved again whenever the light moves"));
  ao_->setToolTip(tr("Screen-space ambient occlusion (32 samples, blurred) on the indirect light"));
  normal_maps_->setToolTip(
      tr("Shade with the materials' normal maps (the bake lights the flat surface)"));
  probes_->setToolTip(
      tr("Each light probe as a small sphere showing the light its SH gives a white "
         "surface facing each way (bake with light probes on)"));
  sphere_->setToolTip(
      tr("A grey sphere (or the mesh loaded with Object…) lit by the probes around it, as a "
         "moving object would be: Shift + drag moves it"));
  load_object_->setToolTip(
      tr("Load a mesh (OBJ, glTF, PLY, ...) to stand for the moving object instead of the "
         "sphere; cancel to go back to the sphere"));
  connect(load_object_, &QPushButton::clicked, this, &PreviewView::choose_object);
  for (QCheckBox* box : {direct_, indirect_, ao_, normal_maps_}) {
    box->setChecked(true);
    connect(box, &QCheckBox::toggled, this, &PreviewView::apply_switches);
  }
  connect(probes_, &QCheckBox::toggled, preview_, &PreviewWidget::set_probes_shown);
  connect(sphere_, &QCheckBox::toggled, preview_, &PreviewWidget::set_sphere_shown);
  show_help();
  auto* row = new QHBoxLayout;
  row->addWidget(direct_);
  row->addWidget(indirect_);
  row->addWidget(ao_);
  row->addWidget(normal_maps_);
  row->addWidget(probes_);
  row->addWidget(sphere_);
  row->addWidget(load_object_);
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

void PreviewView::show_help() {
  const bool probes = preview_->has_probes();
  for (QWidget* w : std::initializer_list<QWidget*>{probes_, sphere_, load_object_})
    w->setEnabled(probes);
  status_->setText(tr("Drag: orbit. Right drag or wheel: zoom. Ctrl + drag: move the light "
                      "(Ctrl + wheel: nearer or farther).%1")
                       .arg(probes ? tr(" Shift + drag: move the %1.")
                                         .arg(QString::fromStdString(preview_->object_name()))
                                   : tr(" No light probes in this bake.")));
}

void PreviewView::choose_object() {
  const QString path = QFileDialog::getOpenFileName(
      this, tr("Moving object"), QString(), tr("Meshes (*.obj *.gltf *.glb *.ply *.stl *.fbx)"));
  try {
    if (path.isEmpty())
      preview_->use_sphere();
    else
      preview_->load_object(path.toStdString());
    sphere_->setChecked(true);
    show_help();
  } catch (const std::exception& e) {
    status_->setText(tr("Object not loaded: %1").arg(QString::fromStdString(e.what())));
  }
}

void PreviewView::set_data(std::shared_ptr<const BakeViewData> bake) {
  try {
    preview_->set_data(std::move(bake));
    show_help();
  } catch (const std::exception& e) {
    preview_->clear();
    status_->setText(tr("No preview: %1").arg(QString::fromStdString(e.what())));
  }
}

}  // namespace bounce::views
