#pragma once
// The bake parameters in artists' terms, each with a tooltip saying what it
// changes on screen, mapped to bounce::BakeSettings (core/bake/bake_settings.h)
// and persisted with QSettings.
#include <QWidget>

#include "bake/bake_settings.h"

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

  void save(QSettings& store) const;
  void load(QSettings& store);

 signals:
  void changed();

 private:
  void update_enabled();

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
};

}  // namespace bounce::studio
