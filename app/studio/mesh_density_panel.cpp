#include "mesh_density_panel.h"

#include <cmath>

#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>

#include "bounce/scene.h"

namespace bounce::studio {

namespace {

enum Column { kName = 0, kPatches = 1, kDensity = 2, kColumns = 3 };

// The spin boxes show two decimals: a density the bake had with more is
// unchanged as long as the box shows its rounded value.
constexpr int kDecimals = 2;
constexpr double kShown = 0.005;

bool shows(const QDoubleSpinBox* box, float density) {
  return std::abs(box->value() - static_cast<double>(density)) < kShown;
}

}  // namespace

MeshDensityPanel::MeshDensityPanel(QWidget* parent)
    : QWidget(parent),
      table_(new QTableWidget(0, kColumns, this)),
      summary_(new QLabel(this)),
      rebake_button_(new QPushButton(tr("Re-bake"), this)),
      reset_button_(new QPushButton(tr("Reset"), this)) {
  table_->setHorizontalHeaderLabels({tr("Mesh"), tr("Patches"), tr("Density")});
  table_->horizontalHeader()->setSectionResizeMode(kName, QHeaderView::Stretch);
  table_->horizontalHeader()->setSectionResizeMode(kPatches, QHeaderView::ResizeToContents);
  table_->horizontalHeader()->setSectionResizeMode(kDensity, QHeaderView::ResizeToContents);
  table_->verticalHeader()->setVisible(false);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setSelectionMode(QAbstractItemView::NoSelection);
  table_->setToolTip(
      tr("Each mesh of the scene with the patches it got in this bake. Density: how many patches "
         "the mesh gets relative to the rest (under a total patch budget the others get fewer; "
         "with patches per voxel its voxels keep that many times more)."));
  rebake_button_->setToolTip(
      tr("Bake again with these densities: a density changes the patches, so the bake re-runs "
         "from its geometry stage (voxels, samples, patches) and everything after it"));
  reset_button_->setToolTip(tr("Set every density back to the bake's"));
  summary_->setWordWrap(true);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(summary_);
  layout->addWidget(table_, 1);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(rebake_button_);
  buttons->addWidget(reset_button_);
  layout->addLayout(buttons);
  connect(rebake_button_, &QPushButton::clicked, this, &MeshDensityPanel::rebake_requested);
  connect(reset_button_, &QPushButton::clicked, this, [this] {
    for (std::size_t i = 0; i < boxes_.size(); ++i)
      boxes_[i]->setValue(static_cast<double>(baked_[i]));
  });
  clear();
}

void MeshDensityPanel::clear() {
  table_->setRowCount(0);
  boxes_.clear();
  baked_.clear();
  editable_ = false;
  summary_->setText(tr("No bake yet: the meshes show once the scene is baked."));
  update_state();
}

void MeshDensityPanel::show_meshes(const std::vector<ManifestMesh>& meshes, bool editable) {
  clear();
  editable_ = editable;
  table_->setRowCount(static_cast<int>(meshes.size()));
  std::size_t total = 0;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const auto row = static_cast<int>(i);
    const ManifestMesh& m = meshes[i];
    auto* name = new QTableWidgetItem(QString::fromStdString(m.name));
    name->setToolTip(tr("%1: %2 m² of surface").arg(QString::fromStdString(m.name)).arg(m.area));
    table_->setItem(row, kName, name);
    auto* count = new QTableWidgetItem(QString::number(m.patches));
    count->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    table_->setItem(row, kPatches, count);
    auto* box = new QDoubleSpinBox(table_);
    box->setDecimals(kDecimals);
    box->setRange(1.0 / 100.0, kMaxPatchDensity);
    box->setSingleStep(0.25);
    box->setValue(static_cast<double>(m.patch_density));
    box->setEnabled(editable);
    connect(box, qOverload<double>(&QDoubleSpinBox::valueChanged), this,
            &MeshDensityPanel::update_state);
    table_->setCellWidget(row, kDensity, box);
    boxes_.push_back(box);
    baked_.push_back(m.patch_density);
    total += m.patches;
  }
  summary_->setText(
      meshes.empty()
          ? tr("This bake's manifest lists no meshes (made before it did).")
          : tr("%n mesh(es), %1 patches.", "", static_cast<int>(meshes.size())).arg(total));
  update_state();
}

QString MeshDensityPanel::mesh_name(int row) const { return table_->item(row, kName)->text(); }

std::size_t MeshDensityPanel::patches(int row) const {
  return table_->item(row, kPatches)->text().toULongLong();
}

void MeshDensityPanel::set_density(int row, double density) {
  boxes_.at(static_cast<std::size_t>(row))->setValue(density);
}

std::vector<float> MeshDensityPanel::densities() const {
  std::vector<float> out = baked_;
  for (std::size_t i = 0; i < boxes_.size(); ++i)
    if (!shows(boxes_[i], baked_[i])) out[i] = static_cast<float>(boxes_[i]->value());
  return out;
}

bool MeshDensityPanel::edited() const { return densities() != baked_; }

void MeshDensityPanel::update_state() {
  const bool changed = edited();
  rebake_button_->setEnabled(editable_ && changed);
  reset_button_->setEnabled(editable_ && changed);
}

}  // namespace bounce::studio
