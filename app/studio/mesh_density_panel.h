#pragma once
// The scene's meshes as a list: each mesh's name, the patches it got in the
// bake shown (the manifest's per-mesh counts) and its patch density, which
// the user may change. "Re-bake" asks for a bake with the densities as
// edited; the core's re-bake plan then re-runs from the geometry stage,
// where the patches are made (everything after depends on them), and a
// re-bake with the densities unchanged reuses the whole bake.
#include <cstddef>
#include <vector>

#include <QString>
#include <QWidget>

#include "bounce/bake_folder.h"

class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QTableWidget;

namespace bounce::studio {

class MeshDensityPanel : public QWidget {
  Q_OBJECT
 public:
  explicit MeshDensityPanel(QWidget* parent = nullptr);

  // Shows a bake's meshes, in mesh order; the densities can be edited when
  // `editable` (the studio holds the scene they were baked from; a bake
  // folder opened on its own is shown read-only).
  void show_meshes(const std::vector<ManifestMesh>& meshes, bool editable);
  void clear();

  int mesh_count() const { return static_cast<int>(baked_.size()); }
  QString mesh_name(int row) const;
  // The patches the mesh got in the bake shown.
  std::size_t patches(int row) const;
  // Sets a density as the user would in its spin box.
  void set_density(int row, double density);
  // The densities as edited, in mesh order: a value left alone (or set back
  // to what its spin box shows of it) is the bake's own, bit for bit.
  std::vector<float> densities() const;
  // Whether some density differs from the bake's.
  bool edited() const;

 signals:
  void rebake_requested();

 private:
  void update_state();

  QTableWidget* table_;
  QLabel* summary_;
  QPushButton* rebake_button_;
  QPushButton* reset_button_;
  std::vector<float> baked_;  // the densities of the bake shown
  std::vector<QDoubleSpinBox*> boxes_;
  bool editable_ = false;
};

}  // namespace bounce::studio
