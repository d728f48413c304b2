#pragma once
// View 1: the scene and its voxel grid. Occupied voxels (voxels.npy) as
// wireframe or translucent cubes over the mesh, filtered by how many samples
// or patches each holds, with an optional slicing plane that cuts mesh and
// voxels along one axis to look inside.
#include <memory>

#include <vtkSmartPointer.h>
#include <QWidget>

#include "bake_view_data.h"

class QCheckBox;
class QComboBox;
class QLabel;
class QSlider;
class QSpinBox;
class QVTKOpenGLNativeWidget;
class vtkActor;
class vtkPlane;
class vtkPolyData;
class vtkRenderer;

namespace bounce::views {

class VoxelView : public QWidget {
  Q_OBJECT
 public:
  enum class Style { Wireframe, Translucent };
  enum class FilterBy { Samples, Patches };
  enum class Axis { X = 0, Y = 1, Z = 2 };

  // The colour voxels are drawn in, unlit, so it stands out from any albedo.
  static constexpr unsigned char kVoxelColour[3] = {0, 200, 255};

  explicit VoxelView(QWidget* parent = nullptr);
  ~VoxelView() override;

  void set_data(std::shared_ptr<const BakeViewData> bake);
  void set_style(Style style);
  // Shows voxels holding at least `min_count` samples or patches.
  void set_filter(FilterBy by, int min_count);
  // `fraction` in [0,1] along `axis` of the grid; keeps what lies below it.
  void set_slice(bool enabled, Axis axis, double fraction);

  std::size_t shown_voxels() const { return shown_; }
  // Renders now and returns the picture (for screenshots and tests).
  QImage render_image();

 private:
  void rebuild_voxels();
  void update_slice();
  void render();

  std::shared_ptr<const BakeViewData> data_;
  QVTKOpenGLNativeWidget* vtk_widget_;
  QComboBox* style_box_;
  QComboBox* filter_box_;
  QSpinBox* min_count_box_;
  QCheckBox* slice_box_;
  QComboBox* axis_box_;
  QSlider* slice_slider_;
  QLabel* status_;
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkActor> mesh_actor_;
  vtkSmartPointer<vtkActor> voxel_actor_;
  vtkSmartPointer<vtkPolyData> voxel_poly_;
  vtkSmartPointer<vtkPlane> slice_plane_;
  std::size_t shown_ = 0;
};

}  // namespace bounce::views
