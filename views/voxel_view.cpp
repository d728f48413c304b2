#include "voxel_view.h"

#include <QVTKOpenGLNativeWidget.h>
#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkPlane.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <QCheckBox>
#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QSlider>
#include <QSpinBox>
#include <QVBoxLayout>

#include "vtk_scene.h"

namespace bounce::views {

VoxelView::VoxelView(QWidget* parent)
    : QWidget(parent),
      vtk_widget_(new QVTKOpenGLNativeWidget(this)),
      style_box_(new QComboBox(this)),
      filter_box_(new QComboBox(this)),
      min_count_box_(new QSpinBox(this)),
      slice_box_(new QCheckBox(tr("Slice"), this)),
      axis_box_(new QComboBox(this)),
      slice_slider_(new QSlider(Qt::Horizontal, this)),
      status_(new QLabel(this)),
      renderer_(vtkSmartPointer<vtkRenderer>::New()),
      voxel_actor_(vtkSmartPointer<vtkActor>::New()),
      voxel_poly_(vtkSmartPointer<vtkPolyData>::New()),
      slice_plane_(vtkSmartPointer<vtkPlane>::New()) {
  style_box_->addItems({tr("Wireframe"), tr("Translucent cubes")});
  style_box_->setToolTip(tr("How occupied voxels are drawn"));
  filter_box_->addItems({tr("Samples"), tr("Patches")});
  filter_box_->setToolTip(tr("Count that the minimum applies to"));
  min_count_box_->setRange(0, 100000);
  min_count_box_->setPrefix(tr("at least "));
  min_count_box_->setToolTip(tr("Show only voxels holding at least this many samples or patches"));
  axis_box_->addItems({"X", "Y", "Z"});
  slice_slider_->setRange(0, 1000);
  slice_slider_->setValue(500);
  slice_box_->setToolTip(tr("Cut the mesh and the voxels along one axis to look inside"));

  // The controls never force a minimum width on the view: at small sizes
  // (screenshots) they are cut off instead.
  auto* bar = new QWidget(this);
  bar->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
  auto* controls = new QHBoxLayout(bar);
  controls->setContentsMargins(0, 0, 0, 0);
  controls->addWidget(style_box_);
  controls->addWidget(new QLabel(tr("Filter by"), this));
  controls->addWidget(filter_box_);
  controls->addWidget(min_count_box_);
  controls->addWidget(slice_box_);
  controls->addWidget(axis_box_);
  controls->addWidget(slice_slider_, 1);
  controls->addWidget(status_);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(bar);
  layout->addWidget(vtk_widget_, 1);

  auto window = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  vtk_widget_->setRenderWindow(window);
  window->AddRenderer(renderer_);
  renderer_->SetBackground(0.12, 0.12, 0.14);

  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(voxel_poly_);
  voxel_actor_->SetMapper(mapper);
  vtkProperty* p = voxel_actor_->GetProperty();
  p->SetColor(kVoxelColour[0] / 255.0, kVoxelColour[1] / 255.0, kVoxelColour[2] / 255.0);
  // Unlit: the voxel colour is the same everywhere on screen.
  p->LightingOff();
  renderer_->AddActor(voxel_actor_);

  connect(style_box_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int) { rebuild_voxels(); });
  connect(filter_box_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int) { rebuild_voxels(); });
  connect(min_count_box_, qOverload<int>(&QSpinBox::valueChanged), this,
          [this](int) { rebuild_voxels(); });
  connect(slice_box_, &QCheckBox::toggled, this, [this](bool) { update_slice(); });
  connect(axis_box_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int) { update_slice(); });
  connect(slice_slider_, &QSlider::valueChanged, this, [this](int) { update_slice(); });
}

VoxelView::~VoxelView() = default;

void VoxelView::set_data(std::shared_ptr<const BakeViewData> bake) {
  data_ = std::move(bake);
  if (mesh_actor_) renderer_->RemoveActor(mesh_actor_);
  mesh_actor_ = nullptr;
  if (data_ && data_->scene) {
    mesh_actor_ = make_scene_mesh_actor(*data_->scene);
    renderer_->AddActor(mesh_actor_);
  }
  rebuild_voxels();
  update_slice();
  if (data_ && data_->scene)
    apply_scene_camera(*data_->scene, *renderer_);
  else
    renderer_->ResetCamera();
  render();
}

void VoxelView::set_style(Style style) { style_box_->setCurrentIndex(static_cast<int>(style)); }

void VoxelView::set_filter(FilterBy by, int min_count) {
  filter_box_->setCurrentIndex(static_cast<int>(by));
  min_count_box_->setValue(min_count);
}

void VoxelView::set_slice(bool enabled, Axis axis, double fraction) {
  axis_box_->setCurrentIndex(static_cast<int>(axis));
  slice_slider_->setValue(static_cast<int>(fraction * slice_slider_->maximum() + 0.5));
  slice_box_->setChecked(enabled);
}

void VoxelView::rebuild_voxels() {
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  auto quads = vtkSmartPointer<vtkCellArray>::New();
  shown_ = 0;
  const bool wire = style_box_->currentIndex() == static_cast<int>(Style::Wireframe);
  if (data_) {
    const bool by_samples = filter_box_->currentIndex() == static_cast<int>(FilterBy::Samples);
    const int min_count = min_count_box_->value();
    const double h = 0.5 * static_cast<double>(data_->cell_size);
    for (const VoxelRow& v : data_->voxels) {
      if ((by_samples ? v.samples : v.patches) < min_count) continue;
      ++shown_;
      const vtkIdType base = points->GetNumberOfPoints();
      for (int corner = 0; corner < 8; ++corner)
        points->InsertNextPoint(v.centre.x + ((corner & 1) ? h : -h),
                                v.centre.y + ((corner & 2) ? h : -h),
                                v.centre.z + ((corner & 4) ? h : -h));
      if (wire) {
        // The 12 edges: corners differing in one bit.
        for (int a = 0; a < 8; ++a)
          for (int bit = 1; bit < 8; bit <<= 1)
            if (!(a & bit)) {
              const vtkIdType ids[2] = {base + a, base + (a | bit)};
              lines->InsertNextCell(2, ids);
            }
      } else {
        static constexpr int kFaces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                             {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
        for (const auto& f : kFaces) {
          const vtkIdType ids[4] = {base + f[0], base + f[1], base + f[2], base + f[3]};
          quads->InsertNextCell(4, ids);
        }
      }
    }
  }
  voxel_poly_->Initialize();
  voxel_poly_->SetPoints(points);
  if (wire)
    voxel_poly_->SetLines(lines);
  else
    voxel_poly_->SetPolys(quads);
  voxel_actor_->GetProperty()->SetOpacity(wire ? 1.0 : 0.3);
  status_->setText(data_ ? tr("%1 of %2 voxels").arg(shown_).arg(data_->voxels.size())
                         : tr("no bake"));
  render();
}

void VoxelView::update_slice() {
  vtkMapper* voxel_mapper = voxel_actor_->GetMapper();
  voxel_mapper->RemoveAllClippingPlanes();
  if (mesh_actor_) mesh_actor_->GetMapper()->RemoveAllClippingPlanes();
  const bool enabled = slice_box_->isChecked() && data_;
  axis_box_->setEnabled(slice_box_->isChecked());
  slice_slider_->setEnabled(slice_box_->isChecked());
  if (enabled) {
    const int axis = axis_box_->currentIndex();
    const TransferGrid& grid = data_->bake.description.grid;
    const double lo = grid.origin[axis];
    const double extent = grid.dims[axis] * static_cast<double>(grid.cell_size);
    const double t = slice_slider_->value() / static_cast<double>(slice_slider_->maximum());
    double origin[3] = {0, 0, 0}, normal[3] = {0, 0, 0};
    origin[axis] = lo + t * extent;
    normal[axis] = -1.0;  // VTK keeps the side the normal points to: below the cut
    slice_plane_->SetOrigin(origin);
    slice_plane_->SetNormal(normal);
    voxel_mapper->AddClippingPlane(slice_plane_);
    if (mesh_actor_) mesh_actor_->GetMapper()->AddClippingPlane(slice_plane_);
  }
  render();
}

void VoxelView::render() { vtk_widget_->renderWindow()->Render(); }

QImage VoxelView::render_image() {
  render();
  return vtk_widget_->grabFramebuffer();
}

}  // namespace bounce::views
