#pragma once
// View 2: the virtual patches as oriented discs (centroid, normal, radius of
// a disc of the patch's area), coloured by albedo, patch id, radiosity under
// the scene's first light, or - once a patch is picked - by that patch's
// form-factor row (who it sees), by its closure (the share of its light that
// lands on sampled surface) or by the scale the form-factor balancing applied
// to its row (where the quadrature struggled), or by the indirect-light error
// the compressed matrix causes under a chosen light (exact T.npy against the
// decoded T.dds: per patch, heat map 0 .. 10%). In that mode a picked patch
// opens a panel with its exact and compressed indirect light per colour and
// the pieces of its compressed row (4x4 blocks, kept entries) ranked by their
// share of the difference (compress/row_error_contributions.h); picking one
// asks the matrix view to mark it.
// Clicking a disc picks its patch and shows its member samples as points.
#include <memory>
#include <optional>
#include <vector>

#include <vtkSmartPointer.h>
#include <QWidget>

#include "bake_view_data.h"
#include "bounce/compression.h"

class QComboBox;
class QLabel;
class QPushButton;
class QTableWidget;
class QVTKOpenGLNativeWidget;
class vtkActor;
class vtkCellPicker;
class vtkGlyph3D;
class vtkPolyData;
class vtkRenderer;

namespace bounce::views {

class ViewJobs;

class PatchView : public QWidget {
  Q_OBJECT
 public:
  enum class ColourBy {
    Albedo,
    PatchId,
    Radiosity,
    FormFactorRow,
    Closure,
    RowScale,
    IndirectError
  };
  // The error map's colour scale runs from 0 to this relative error.
  static constexpr double kErrorFullScale = 0.1;

  // Rows of the panel's table: the largest shares of the picked patch's error.
  static constexpr int kSourcesShown = 12;

  // Colour of the picked patch's member samples.
  static constexpr unsigned char kSampleColour[3] = {255, 0, 255};

  // The radiosity and the indirect-light error are computed on `jobs` (the
  // core's bake_patch_light.h); the other colourings map data at hand.
  explicit PatchView(ViewJobs& jobs, QWidget* parent = nullptr);
  ~PatchView() override;

  void set_data(std::shared_ptr<const BakeViewData> bake);
  // FormFactorRow needs F.npy and a picked patch, Closure and RowScale
  // closure.npy; otherwise they fall back to albedo.
  void set_colour_by(ColourBy by);
  // The light of IndirectError: 0 = the scene's lights together (the first
  // hit `bounce solve` lights the bake with), k >= 1 = evaluation light k - 1
  // (lights_first_hit.npy).
  void set_error_light(int index);
  // IndirectError needs the exact T.npy and a compressed matrix: whether this
  // bake has both, and the area-weighted relative RMS error of the indirect
  // light last shown (the bake's figure, `bounce solve --compare-exact`'s
  // patch_indirect_rel_rms for light 0).
  bool can_show_indirect_error() const;
  double indirect_error_rms() const { return error_rms_; }
  QString status_text() const;
  // Picks patch `p` (-1: none).
  void select_patch(int p);
  int selected_patch() const { return selected_; }
  // The patch whose disc is under pixel (x, y) of the 3-D view, i.e. the VTK
  // widget below the control bar (Qt coordinates, top-left origin), or -1.
  int patch_at(int x, int y);
  // Where patch p's centroid lands in the 3-D view's pixels (the VTK widget's
  // Qt coordinates, as patch_at takes them).
  QPoint project_patch(int p);
  // RGB of each patch disc as last coloured (for tests).
  const std::vector<std::array<unsigned char, 3>>& patch_colours() const { return colours_; }
  QImage render_image();
  // The picked patch's row explained under the error light (IndirectError
  // with a picked patch), else null; the panel shows its first
  // kSourcesShown sources, in its order.
  const RowErrorContributions* row_explanation() const {
    return explanation_ ? &*explanation_ : nullptr;
  }
  QString explanation_text() const;
  QTableWidget* sources_table() const { return sources_; }
  QPushButton* matrix_button() const { return matrix_button_; }
  // Picks row `rank` of the table (emits error_source_selected).
  void select_source(int rank);

 signals:
  void patch_selected(int patch);
  // A source of the picked patch's error was picked: `patch`'s row, stored
  // row `stored_row`, stored columns [stored_col_first, stored_col_last).
  void error_source_selected(int patch, int stored_row, int stored_col_first, int stored_col_last);
  // The panel's button: show the picked source in the matrix view.
  void matrix_requested();

 private:
  // Colours the patches as the menus say: at once, or through a job whose
  // result colours them when it arrives.
  void recolour();
  void colour_by_radiosity();
  void colour_by_indirect_error();
  // Shows colours_ with `what` in the status.
  void show_colours(const QString& what);
  // Shows `what` while a job computes the colours (the last ones stay).
  void show_pending(const QString& what);
  // Fills the panel from explanation_ (hides it when there is none).
  void show_explanation();
  void emit_source(int rank);
  void show_samples();
  void render();

  // The one job of this view: the colours being computed.
  static constexpr int kColourJob = 0;

  ViewJobs& jobs_;
  std::shared_ptr<const BakeViewData> data_;
  QVTKOpenGLNativeWidget* vtk_widget_;
  QComboBox* colour_box_;
  QComboBox* light_box_;
  QLabel* status_;
  QWidget* explain_;
  QLabel* explain_text_;
  QTableWidget* sources_;
  QPushButton* matrix_button_;
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkPolyData> centres_;
  vtkSmartPointer<vtkGlyph3D> glyphs_;
  vtkSmartPointer<vtkActor> disc_actor_;
  vtkSmartPointer<vtkPolyData> sample_poly_;
  vtkSmartPointer<vtkActor> sample_actor_;
  vtkSmartPointer<vtkCellPicker> picker_;
  std::vector<std::array<unsigned char, 3>> colours_;
  int selected_ = -1;
  // The decoded compressed matrix (stored channels, patch order), made by
  // the job when IndirectError first needs it.
  std::shared_ptr<const std::vector<std::vector<float>>> decoded_;
  double error_rms_ = 0.0;
  std::optional<RowErrorContributions> explanation_;
};

}  // namespace bounce::views
