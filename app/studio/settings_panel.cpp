#include "settings_panel.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QSettings>
#include <QSpinBox>
#include <algorithm>
#include <cmath>
#include <variant>

namespace bounce::studio {

namespace {

// Bounces menu: its named values (auto, infinite), then fixed counts.
constexpr int kFixedBouncesShown = 16;
// Double spin boxes cannot exclude a bound: they stop one step inside it.
constexpr int kBudgetDecimals = 3;

QString text_of(const SettingRow& row, const SettingValue& v) {
  return QString::fromStdString(setting_text(row, v));
}

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
      budget_box_(new QDoubleSpinBox(this)),
      size_limit_box_(new QDoubleSpinBox(this)),
      gather_rays_box_(new QSpinBox(this)),
      near_box_(new QDoubleSpinBox(this)),
      near_min_rays_box_(new QSpinBox(this)),
      spots_box_(new QSpinBox(this)),
      probes_box_(new QComboBox(this)) {
  grid_box_->addItems({tr("Scene's own"), tr("Voxel size"), tr("Total patches")});
  grid_box_->setToolTip(
      tr("How fine the patch grid is: as the scene file suggests, by voxel size, or by the "
         "number of patches you want in total (the voxel size is then chosen for you)"));
  voxel_box_->setSuffix(tr(" voxels across"));
  kept_box_->setDecimals(4);
  kept_box_->setSingleStep(0.01);
  budget_box_->setDecimals(kBudgetDecimals);
  budget_box_->setSingleStep(0.01);
  size_limit_box_->setDecimals(kBudgetDecimals);
  size_limit_box_->setSingleStep(0.025);
  add_control("voxel_resolution", voxel_box_);
  add_control("patches_total", patches_total_box_);
  add_control("patches_per_voxel", per_voxel_box_);
  add_control("patch_mode", patch_mode_box_);
  add_control("bounces", bounces_box_);
  add_control("codec", codec_box_);
  add_control("ordering", ordering_box_);
  add_control("kept_fraction", kept_box_);
  add_control("error_budget", budget_box_);
  add_control("size_limit", size_limit_box_);
  // The final gather's settings, last: they decide how sharp the lit mesh
  // is and how long every light move takes in the preview.
  gather_rays_box_->setSingleStep(64);
  near_box_->setDecimals(3);
  near_box_->setSingleStep(0.05);
  add_control("final_gather_rays", gather_rays_box_);
  add_control("final_gather_near", near_box_);
  add_control("final_gather_near_min_rays", near_min_rays_box_);
  add_control("final_gather_spots", spots_box_);
  add_control("light_probes", probes_box_);
  // Where the spin boxes start when the setting is left to the scene or the codec.
  voxel_box_->setValue(BakeSettings::kDefaultVoxelResolution);
  patches_total_box_->setValue(2048);
  per_voxel_box_->setValue(BakeSettings::kDefaultPatchesPerVoxel);
  kept_box_->setValue(kPaperKeptFraction);
  budget_box_->setValue(BakeSettings::kDefaultErrorBudget);
  size_limit_box_->setValue(BakeSettings::kDefaultSizeLimit);
  const BakeSettings defaults;
  gather_rays_box_->setValue(defaults.final_gather_rays);
  near_box_->setValue(defaults.final_gather_near);
  near_min_rays_box_->setValue(defaults.final_gather_near_min_rays);
  spots_box_->setValue(defaults.final_gather_spots);
  kept_mode_box_->addItems({tr("from error budget"), tr("fixed share")});
  kept_mode_box_->setToolTip(
      tr("Which of the matrix's largest values are kept exactly: as few as meet the error "
         "budget, or a fixed share"));

  auto* form = new QFormLayout(this);
  form->addRow(tr("Grid"), grid_box_);
  for (const auto& [row, control] : controls_) {
    if (control == kept_box_) form->addRow(tr("Kept values"), kept_mode_box_);
    form->addRow(tr(row->label), control);
  }

  // Controls that decide which others apply refresh the enabled states.
  const auto refresh = [this] {
    update_enabled();
    emit changed();
  };
  for (QComboBox* box :
       {grid_box_, patch_mode_box_, bounces_box_, codec_box_, ordering_box_, kept_mode_box_})
    connect(box, qOverload<int>(&QComboBox::currentIndexChanged), this, refresh);
  connect(probes_box_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          &SettingsPanel::changed);
  connect(gather_rays_box_, qOverload<int>(&QSpinBox::valueChanged), this, refresh);
  connect(near_box_, qOverload<double>(&QDoubleSpinBox::valueChanged), this, refresh);
  for (QSpinBox* box :
       {voxel_box_, patches_total_box_, per_voxel_box_, near_min_rays_box_, spots_box_})
    connect(box, qOverload<int>(&QSpinBox::valueChanged), this, &SettingsPanel::changed);
  for (QDoubleSpinBox* box : {kept_box_, budget_box_, size_limit_box_})
    connect(box, qOverload<double>(&QDoubleSpinBox::valueChanged), this, &SettingsPanel::changed);
  update_enabled();
}

void SettingsPanel::add_control(const char* setting, QWidget* control) {
  const SettingRow& row = setting_row(setting);
  control->setToolTip(tr(row.studio_help));
  if (auto* spin = qobject_cast<QSpinBox*>(control)) {
    spin->setRange(static_cast<int>(row.min), static_cast<int>(row.max));
  } else if (auto* real = qobject_cast<QDoubleSpinBox*>(control)) {
    const double step = std::pow(10.0, -real->decimals());
    real->setRange(row.min + (row.min_exclusive ? step : 0.0),
                   row.max - (row.max_exclusive ? step : 0.0));
  } else if (auto* box = qobject_cast<QComboBox*>(control)) {
    // Each entry's data is the setting's text, which parse_setting reads back.
    if (row.optional) box->addItem(tr(row.unset_label), QString(row.unset));
    for (const SettingChoice& c : row.choices) box->addItem(tr(c.label), QString(c.name));
    for (const NamedValue& n : row.named)
      if (n.label) box->addItem(tr(n.label), QString(n.name));
    if (!row.named.empty())
      for (int k = 1; k <= kFixedBouncesShown && k <= row.max; ++k)
        box->addItem(QString::number(k), QString::number(k));
    show_value(row, box, row.get(BakeSettings{}));
  }
  controls_.emplace_back(&row, control);
}

SettingValue SettingsPanel::value_of(const SettingRow& row, const QWidget* control) const {
  if (const auto* box = qobject_cast<const QSpinBox*>(control))
    return static_cast<std::int64_t>(box->value());
  if (const auto* box = qobject_cast<const QDoubleSpinBox*>(control)) return box->value();
  const auto* box = qobject_cast<const QComboBox*>(control);
  return parse_setting(row, box->currentData().toString().toStdString());
}

void SettingsPanel::show_value(const SettingRow& row, QWidget* control, const SettingValue& value) {
  if (auto* box = qobject_cast<QComboBox*>(control)) {
    if (const int k = box->findData(text_of(row, value)); k >= 0) box->setCurrentIndex(k);
  } else if (const auto* v = std::get_if<std::int64_t>(&value)) {
    qobject_cast<QSpinBox*>(control)->setValue(static_cast<int>(*v));
  } else if (const auto* x = std::get_if<double>(&value)) {
    qobject_cast<QDoubleSpinBox*>(control)->setValue(*x);
  }
}

void SettingsPanel::update_enabled() {
  const auto grid = static_cast<GridChoice>(grid_box_->currentIndex());
  voxel_box_->setEnabled(grid == GridChoice::VoxelSize);
  patches_total_box_->setEnabled(grid == GridChoice::PatchesTotal);
  const QString codec = codec_box_->currentData().toString();
  const bool compressed = codec != to_string(CodecChoice::Dense);
  const bool paper = codec == to_string(CodecChoice::LargestEntries);
  // The paper's codec has no error budget: it keeps a fixed share.
  kept_mode_box_->setEnabled(compressed && !paper);
  ordering_box_->setEnabled(compressed);
  const bool fixed = paper || kept_mode_box_->currentIndex() == 1;
  kept_box_->setEnabled(compressed && fixed);
  budget_box_->setEnabled(compressed && !fixed);
  // The size limit bounds the budget's search; a fixed share has none.
  size_limit_box_->setEnabled(compressed && !fixed);
  // Near sources are part of the final gather; their threshold needs some.
  const bool gather = gather_rays_box_->value() > 0;
  near_box_->setEnabled(gather);
  near_min_rays_box_->setEnabled(gather && near_box_->value() > 0.0);
  spots_box_->setEnabled(gather);
}

BakeSettings SettingsPanel::settings() const {
  BakeSettings s;
  // The menus always apply; a number only while its box is enabled (the
  // grid choice and the kept-values mode decide which).
  for (const auto& [row, control] : controls_)
    if (qobject_cast<const QComboBox*>(control) || control->isEnabled())
      row->set(s, value_of(*row, control));
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
  codec_box_->setCurrentIndex(codec_box_->findData(QString(to_string(codec))));
}

void SettingsPanel::set_ordering(std::optional<OrderingMethod> ordering) {
  BakeSettings s;
  s.ordering = ordering;
  const SettingRow& row = setting_row("ordering");
  show_value(row, ordering_box_, row.get(s));
}

void SettingsPanel::set(const std::string& setting, const std::string& text) {
  for (const auto& [row, control] : controls_)
    if (setting == row->name) show_value(*row, control, parse_setting(*row, text));
}

void SettingsPanel::apply(const BakeSettings& s) {
  if (s.patches_total)
    set_grid(GridChoice::PatchesTotal, *s.patches_total);
  else if (s.voxel_resolution)
    set_grid(GridChoice::VoxelSize, *s.voxel_resolution);
  for (const auto& [row, control] : controls_) {
    if (control == voxel_box_ || control == patches_total_box_) continue;  // the grid, above
    const SettingValue v = row->get(s);
    if (!std::holds_alternative<std::monostate>(v)) show_value(*row, control, v);
  }
  if (s.kept_fraction)
    kept_mode_box_->setCurrentIndex(1);
  else if (s.codec == CodecChoice::LightWeighted)
    kept_mode_box_->setCurrentIndex(0);
  update_enabled();
}

void SettingsPanel::save(QSettings& store) const {
  store.beginGroup("bake");
  store.setValue("grid", grid_box_->currentIndex());
  store.setValue("kept_mode", kept_mode_box_->currentIndex());
  // Each setting under its name; menus by the chosen entry's name.
  for (const auto& [row, control] : controls_)
    store.setValue(row->name, text_of(*row, value_of(*row, control)));
  store.endGroup();
}

void SettingsPanel::load(QSettings& store) {
  store.beginGroup("bake");
  // Values out of range are clamped by the widgets; unknown menu entries and
  // unreadable values keep the panel's.
  grid_box_->setCurrentIndex(std::clamp(store.value("grid", 0).toInt(), 0, 2));
  kept_mode_box_->setCurrentIndex(std::clamp(store.value("kept_mode", 0).toInt(), 0, 1));
  for (const auto& [row, control] : controls_) {
    const QVariant stored = store.value(row->name);
    if (!stored.isValid()) continue;
    if (auto* box = qobject_cast<QComboBox*>(control)) {
      if (const int k = box->findData(stored.toString()); k >= 0) box->setCurrentIndex(k);
    } else if (auto* spin = qobject_cast<QSpinBox*>(control)) {
      bool ok = false;
      const int v = stored.toInt(&ok);
      if (ok) spin->setValue(v);
    } else if (auto* real = qobject_cast<QDoubleSpinBox*>(control)) {
      bool ok = false;
      const double v = stored.toDouble(&ok);
      if (ok) real->setValue(v);
    }
  }
  store.endGroup();
  update_enabled();
}

}  // namespace bounce::studio
