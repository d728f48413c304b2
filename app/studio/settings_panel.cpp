#include "settings_panel.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QSettings>
#include <QSpinBox>

#include "transport/transport_settings.h"

namespace bounce::studio {

namespace {

// Bounces menu: auto, infinite, then fixed counts.
constexpr int kFixedBouncesShown = 16;
// Ordering menu: the codec's own ordering (BakeSettings::ordering unset).
constexpr int kAutoOrdering = -1;

}  // namespace

SettingsPanel::SettingsPanel(QWidget* parent)
    : QWidget(parent),
      grid_box_(new QComboBox(this)),
      voxel_box_(new QSpinBox(this)),
      patches_total_box_(new QSpinBox(this)),
      per_voxel_box_(new QSpinBox(this)),
      patch_mode_box_(new QComboBox(this)),
      bounces_box_(new QComboBox(this)),
      codec_box_(new QComboBox(this)),
      ordering_box_(new QComboBox(this)),
      kept_mode_box_(new QComboBox(this)),
      kept_box_(new QDoubleSpinBox(this)),
      budget_box_(new QDoubleSpinBox(this)) {
  grid_box_->addItems({tr("Scene's own"), tr("Voxel size"), tr("Total patches")});
  grid_box_->setToolTip(
      tr("How fine the patch grid is: as the scene file suggests, by voxel size, or by the "
         "number of patches you want in total (the voxel size is then chosen for you)"));
  voxel_box_->setRange(1, 512);
  voxel_box_->setValue(BakeSettings::kDefaultVoxelResolution);
  voxel_box_->setSuffix(tr(" voxels across"));
  voxel_box_->setToolTip(
      tr("Voxels along the scene's longest side. More voxels: smaller patches, finer light "
         "detail, longer bakes (patch count grows about with the square)"));
  patches_total_box_->setRange(1, 1 << 20);
  patches_total_box_->setValue(2048);
  patches_total_box_->setToolTip(
      tr("Aim for about this many patches; the bake picks the voxel size that comes closest"));
  per_voxel_box_->setRange(1, 64);
  per_voxel_box_->setValue(BakeSettings::kDefaultPatchesPerVoxel);
  per_voxel_box_->setToolTip(
      tr("Patches kept in each voxel after clustering its samples. 3 keeps the three walls of "
         "a room corner apart; more subdivides flat surfaces"));
  patch_mode_box_->addItem(tr("virtual patches"), static_cast<int>(PatchMode::Virtual));
  patch_mode_box_->addItem(tr("voxel baseline"), static_cast<int>(PatchMode::Voxel));
  patch_mode_box_->setToolTip(
      tr("virtual: the samples in each voxel clustered into patches (the method); voxel "
         "baseline: one patch per voxel, for comparison"));
  bounces_box_->addItem(tr("auto"), TransportSettings::kAutoBounces);
  bounces_box_->addItem(tr("infinite (exact)"), TransportSettings::kInfiniteBounces);
  for (int k = 1; k <= kFixedBouncesShown; ++k) bounces_box_->addItem(QString::number(k), k);
  bounces_box_->setToolTip(
      tr("How many times light bounces between surfaces. auto: until the next bounce adds "
         "less than 0.1%; infinite: the exact limit"));
  codec_box_->addItem(tr("auto"), static_cast<int>(CodecChoice::Auto));
  codec_box_->addItem(tr("dense (exact)"), static_cast<int>(CodecChoice::Dense));
  codec_box_->addItem(tr("paper (published BC1)"), static_cast<int>(CodecChoice::Paper));
  codec_box_->addItem(tr("ours"), static_cast<int>(CodecChoice::Ours));
  codec_box_->setToolTip(
      tr("How the light-transport matrix is stored. dense: exact and large; paper: the "
         "published DXT1 pipeline; ours: smaller for the same error; auto: ours, or dense "
         "when the matrix is too small for compression to pay"));
  ordering_box_->addItem(tr("codec's own"), kAutoOrdering);
  ordering_box_->addItem(tr("none (patch order)"), static_cast<int>(OrderingMethod::None));
  ordering_box_->addItem(tr("paper, 1 pass"), static_cast<int>(OrderingMethod::Paper1));
  ordering_box_->addItem(tr("paper, 2 passes"), static_cast<int>(OrderingMethod::Paper2));
  ordering_box_->addItem(tr("ours"), static_cast<int>(OrderingMethod::Ours));
  ordering_box_->setToolTip(
      tr("The order of the matrix rows and columns before they are cut into 4x4 blocks: "
         "similar rows side by side make smoother blocks and less compression error (see the "
         "Matrix view's right half). codec's own: paper's 2-pass tour for paper, ours for ours; "
         "paper: the published greedy tour (slow on large matrices); none: patch order. "
         "Changing it re-runs only the compression"));
  kept_mode_box_->addItems({tr("from error budget"), tr("fixed share")});
  kept_mode_box_->setToolTip(
      tr("Which of the matrix's largest values are kept exactly: as few as meet the error "
         "budget, or a fixed share"));
  kept_box_->setRange(0.0, 1.0);
  kept_box_->setDecimals(4);
  kept_box_->setSingleStep(0.01);
  kept_box_->setValue(0.04);
  kept_box_->setToolTip(
      tr("Share of each colour's matrix values kept exactly (the paper keeps 0.04). More: "
         "less error, larger bake"));
  budget_box_->setRange(0.001, 0.999);
  budget_box_->setDecimals(3);
  budget_box_->setSingleStep(0.01);
  budget_box_->setValue(BakeSettings::kDefaultErrorBudget);
  budget_box_->setToolTip(
      tr("Relative RMS error of the indirect light the compressed matrix may cause, on the "
         "worst evaluation light (0.02 = 2%); the codec keeps the fewest exact values that "
         "meet it"));

  auto* form = new QFormLayout(this);
  form->addRow(tr("Grid"), grid_box_);
  form->addRow(tr("Voxel size"), voxel_box_);
  form->addRow(tr("Total patches"), patches_total_box_);
  form->addRow(tr("Patches per voxel"), per_voxel_box_);
  form->addRow(tr("Patches"), patch_mode_box_);
  form->addRow(tr("Bounces"), bounces_box_);
  form->addRow(tr("Codec"), codec_box_);
  form->addRow(tr("Ordering"), ordering_box_);
  form->addRow(tr("Kept values"), kept_mode_box_);
  form->addRow(tr("Kept fraction"), kept_box_);
  form->addRow(tr("Error budget"), budget_box_);

  for (QComboBox* box :
       {grid_box_, patch_mode_box_, bounces_box_, codec_box_, ordering_box_, kept_mode_box_})
    connect(box, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int) {
      update_enabled();
      emit changed();
    });
  for (QSpinBox* box : {voxel_box_, patches_total_box_, per_voxel_box_})
    connect(box, qOverload<int>(&QSpinBox::valueChanged), this, &SettingsPanel::changed);
  for (QDoubleSpinBox* box : {kept_box_, budget_box_})
    connect(box, qOverload<double>(&QDoubleSpinBox::valueChanged), this, &SettingsPanel::changed);
  update_enabled();
}

void SettingsPanel::update_enabled() {
  const auto grid = static_cast<GridChoice>(grid_box_->currentIndex());
  voxel_box_->setEnabled(grid == GridChoice::VoxelSize);
  patches_total_box_->setEnabled(grid == GridChoice::PatchesTotal);
  const auto codec = static_cast<CodecChoice>(codec_box_->currentData().toInt());
  const bool compressed = codec != CodecChoice::Dense;
  // The paper's codec has no error budget: it keeps a fixed share.
  kept_mode_box_->setEnabled(compressed && codec != CodecChoice::Paper);
  ordering_box_->setEnabled(compressed);
  const bool fixed = codec == CodecChoice::Paper || kept_mode_box_->currentIndex() == 1;
  kept_box_->setEnabled(compressed && fixed);
  budget_box_->setEnabled(compressed && !fixed);
}

BakeSettings SettingsPanel::settings() const {
  BakeSettings s;
  switch (static_cast<GridChoice>(grid_box_->currentIndex())) {
    case GridChoice::SceneDefault:
      break;
    case GridChoice::VoxelSize:
      s.voxel_resolution = voxel_box_->value();
      break;
    case GridChoice::PatchesTotal:
      s.patches_total = patches_total_box_->value();
      break;
  }
  s.patches_per_voxel = per_voxel_box_->value();
  s.patch_mode = static_cast<PatchMode>(patch_mode_box_->currentData().toInt());
  s.transport.bounces = bounces_box_->currentData().toInt();
  s.codec = static_cast<CodecChoice>(codec_box_->currentData().toInt());
  if (const int o = ordering_box_->currentData().toInt(); o != kAutoOrdering)
    s.ordering = static_cast<OrderingMethod>(o);
  if (kept_box_->isEnabled()) s.kept_fraction = kept_box_->value();
  if (budget_box_->isEnabled()) s.error_budget = budget_box_->value();
  s.dump_matrices = true;
  s.pictures = true;
  return s;
}

void SettingsPanel::set_grid(GridChoice choice, int value) {
  grid_box_->setCurrentIndex(static_cast<int>(choice));
  if (choice == GridChoice::VoxelSize) voxel_box_->setValue(value);
  if (choice == GridChoice::PatchesTotal) patches_total_box_->setValue(value);
}

void SettingsPanel::set_codec(CodecChoice codec) {
  codec_box_->setCurrentIndex(codec_box_->findData(static_cast<int>(codec)));
}

void SettingsPanel::set_ordering(std::optional<OrderingMethod> ordering) {
  ordering_box_->setCurrentIndex(
      ordering_box_->findData(ordering ? static_cast<int>(*ordering) : kAutoOrdering));
}

void SettingsPanel::apply(const BakeSettings& s) {
  if (s.patches_total)
    set_grid(GridChoice::PatchesTotal, *s.patches_total);
  else if (s.voxel_resolution)
    set_grid(GridChoice::VoxelSize, *s.voxel_resolution);
  if (s.patches_per_voxel) per_voxel_box_->setValue(*s.patches_per_voxel);
  patch_mode_box_->setCurrentIndex(patch_mode_box_->findData(static_cast<int>(s.patch_mode)));
  if (const int k = bounces_box_->findData(s.transport.bounces); k >= 0)
    bounces_box_->setCurrentIndex(k);
  set_codec(s.codec);
  if (s.kept_fraction) {
    kept_mode_box_->setCurrentIndex(1);
    kept_box_->setValue(*s.kept_fraction);
  } else if (s.codec == CodecChoice::Ours) {
    kept_mode_box_->setCurrentIndex(0);
  }
  update_enabled();
}

void SettingsPanel::save(QSettings& store) const {
  store.beginGroup("bake");
  store.setValue("grid", grid_box_->currentIndex());
  store.setValue("voxel", voxel_box_->value());
  store.setValue("patches_total", patches_total_box_->value());
  store.setValue("patches_per_voxel", per_voxel_box_->value());
  store.setValue("patch_mode", patch_mode_box_->currentData());
  store.setValue("bounces", bounces_box_->currentData());
  store.setValue("codec", codec_box_->currentData());
  store.setValue("ordering", ordering_box_->currentData());
  store.setValue("kept_mode", kept_mode_box_->currentIndex());
  store.setValue("kept_fraction", kept_box_->value());
  store.setValue("error_budget", budget_box_->value());
  store.endGroup();
}

void SettingsPanel::load(QSettings& store) {
  store.beginGroup("bake");
  // Values out of range are clamped by the widgets; unknown menu entries keep the default.
  grid_box_->setCurrentIndex(std::clamp(store.value("grid", 0).toInt(), 0, 2));
  voxel_box_->setValue(store.value("voxel", voxel_box_->value()).toInt());
  patches_total_box_->setValue(store.value("patches_total", patches_total_box_->value()).toInt());
  per_voxel_box_->setValue(store.value("patches_per_voxel", per_voxel_box_->value()).toInt());
  if (const int k =
          patch_mode_box_->findData(store.value("patch_mode", patch_mode_box_->currentData()));
      k >= 0)
    patch_mode_box_->setCurrentIndex(k);
  if (const int k = bounces_box_->findData(store.value("bounces", bounces_box_->currentData()));
      k >= 0)
    bounces_box_->setCurrentIndex(k);
  if (const int k = codec_box_->findData(store.value("codec", codec_box_->currentData())); k >= 0)
    codec_box_->setCurrentIndex(k);
  if (const int k = ordering_box_->findData(store.value("ordering", kAutoOrdering)); k >= 0)
    ordering_box_->setCurrentIndex(k);
  kept_mode_box_->setCurrentIndex(std::clamp(store.value("kept_mode", 0).toInt(), 0, 1));
  kept_box_->setValue(store.value("kept_fraction", kept_box_->value()).toDouble());
  budget_box_->setValue(store.value("error_budget", budget_box_->value()).toDouble());
  store.endGroup();
  update_enabled();
}

}  // namespace bounce::studio
