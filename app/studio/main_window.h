#pragma once
// Bounce Studio's main window: open a scene (dialog, recent files, drag and
// drop) or a bake folder, tune the bake settings, bake on a worker thread
// with a progress bar per stage, ETA and Cancel, look at the result in the
// views' tabs, set each mesh's patch density in the mesh list and re-bake,
// export the bake folder. Errors go to message boxes.
#include <memory>

#include <QMainWindow>

#include "bake_controller.h"

class QLabel;
class QMenu;
class QProgressBar;
class QPushButton;
class QTabWidget;
class QVBoxLayout;

namespace bounce::views {
class ErrorView;
class MatrixView;
class PatchView;
class ReportView;
class PreviewView;
class ViewJobs;
class VoxelView;
}  // namespace bounce::views

namespace bounce::studio {

class MeshDensityPanel;
class SettingsPanel;

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  enum class Tab { Voxels = 0, Patches = 1, Matrix = 2, Error = 3, Preview = 4 };

  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  // Opens a scene (remembered in recent files) or a bake folder.
  void open(const QString& path);
  void show_data(std::shared_ptr<const views::BakeViewData> bake);
  void show_tab(Tab tab);
  SettingsPanel* settings_panel() const { return settings_; }
  MeshDensityPanel* mesh_panel() const { return meshes_; }
  views::VoxelView* voxel_view() const { return voxel_view_; }
  views::PatchView* patch_view() const { return patch_view_; }
  views::MatrixView* matrix_view() const { return matrix_view_; }
  views::ReportView* report_view() const { return report_view_; }

 protected:
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;
  void closeEvent(QCloseEvent* event) override;

 private:
  void build_menus();
  // The report tab: the error-against-run-time chart, its quick sweep on a
  // worker thread, report.json files, clicked points into the settings panel.
  void build_report_tab();
  // The mesh list (a dock): each mesh's patches and its density, which a
  // re-bake applies.
  void build_mesh_dock();
  // Fills the mesh list from a bake folder's manifest; editable when the
  // studio holds the scene it was baked from.
  void show_meshes(const views::BakeViewData& bake, bool editable);
  void rebuild_recent_menu();
  void start_bake();
  void export_bake_folder();
  void export_lit_glb();
  void on_stage_progress(const QString& stage, double fraction, double eta);
  void set_busy(bool busy);
  void show_error(const QString& what, const QString& message);
  // Shows the finished bake (or the cached one) and says what was run.
  void on_bake_finished(std::shared_ptr<const BakeJobResult> job);
  // Shows a bake in progress (BakeController::partial).
  void show_partial(std::shared_ptr<const views::BakeViewData> bake);

  // The one background thread of the studio: the views' computations, the
  // bake and the report sweep. Made before the views and the controllers
  // (they keep a reference) and, as the first of this window's children,
  // deleted before them: it stops and joins its running job, whose result
  // is then dropped.
  views::ViewJobs* jobs_;
  SettingsPanel* settings_;
  MeshDensityPanel* meshes_;
  BakeController* controller_;
  QTabWidget* tabs_;
  views::VoxelView* voxel_view_;
  views::PatchView* patch_view_;
  views::MatrixView* matrix_view_;
  views::ErrorView* error_view_;
  views::PreviewView* preview_view_;
  QPushButton* bake_button_;
  QPushButton* cancel_button_;
  QVBoxLayout* stage_bars_;
  QLabel* scene_label_;
  QMenu* recent_menu_ = nullptr;
  QAction* export_action_ = nullptr;
  QAction* export_glb_action_ = nullptr;
  QString scene_path_;
  QString current_stage_;
  QProgressBar* current_bar_ = nullptr;
  QLabel* current_eta_ = nullptr;
  std::shared_ptr<const BakeJobResult> last_job_;
  views::ReportView* report_view_ = nullptr;
  class ReportController* report_controller_ = nullptr;
};

}  // namespace bounce::studio
