#pragma once
// The bake parameters in artists' terms, each with a tooltip saying what it
// changes on screen, mapped to bounce::BakeSettings and persisted with
// QSettings. Each control is built from its row of the settings table
// (bounce/settings.h): label, tooltip, range, default, menu entries; the
// store keeps each setting under its name, and choices by name.
#include <QWidget>
#include <string>
#include <utility>
#include <vector>

#include "bounce/settings.h"

class QComboBox;
class QDoubleSpinBox;
class QSettings;
class QSpinBox;

namespace bounce::studio {

class SettingsPanel : public QWidget {
  Q_OBJECT
 public:
  enum class GridChoice { SceneDefault = 0, VoxelSize = 1, PatchesTotal = 2 };

  explicit SettingsPanel(QWidget* parent = nullptr);

  // The settings a bake gets. The studio always keeps F and the exact T in
  // its bake folders (dump_matrices): the views show them.
  BakeSettings settings() const;

  void set_grid(GridChoice choice, int value);
  void set_codec(CodecChoice codec);
  // Shows `settings` in the panel (the report view's clicked point): grid,
  // patch mode, bounces, codec and kept share; unset values keep the panel's.
  void apply(const BakeSettings& settings);
  // Unset: the codec's own ordering.
  void set_ordering(std::optional<OrderingMethod> ordering);
  // Sets a setting's control from its text as the command line gives it
  // (e.g. "codec", "paper"); throws BakeSettings::InvalidSetting.
  void set(const std::string& setting, const std::string& text);

  void save(QSettings& store) const;
  void load(QSettings& store);

 signals:
  void changed();

 private:
  void update_enabled();
  // The control of a row of the settings table, set up from the row.
  void add_control(const char* setting, QWidget* control);
  SettingValue value_of(const SettingRow& row, const QWidget* control) const;
  void show_value(const SettingRow& row, QWidget* control, const SettingValue& value);

  QComboBox* grid_box_;
  QSpinBox* voxel_box_;
  QSpinBox* patches_total_box_;
  QSpinBox* per_voxel_box_;
  QComboBox* patch_mode_box_;
  QComboBox* bounces_box_;
  QComboBox* codec_box_;
  QComboBox* ordering_box_;
  QComboBox* kept_mode_box_;
  QDoubleSpinBox* kept_box_;
  QDoubleSpinBox* budget_box_;
  QDoubleSpinBox* size_limit_box_;
  QSpinBox* gather_rays_box_;
  QDoubleSpinBox* near_box_;
  QSpinBox* near_min_rays_box_;
  QSpinBox* spots_box_;
  QComboBox* probes_box_;
  // Every control that shows one setting, in the settings table's order.
  std::vector<std::pair<const SettingRow*, QWidget*>> controls_;
};

}  // namespace bounce::studio
