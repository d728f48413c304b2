#include "vtk_scene.h"

#include <algorithm>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

namespace bounce::views {

vtkSmartPointer<vtkActor> make_scene_mesh_actor(const Scene& scene) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetNumberOfPoints(static_cast<vtkIdType>(scene.positions.size()));
  for (std::size_t k = 0; k < scene.positions.size(); ++k) {
    const glm::vec3& p = scene.positions[k];
    points->SetPoint(static_cast<vtkIdType>(k), p.x, p.y, p.z);
  }
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetName("albedo");
  colours->SetNumberOfComponents(3);
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    const glm::uvec3& tri = scene.triangles[t];
    const vtkIdType ids[3] = {tri.x, tri.y, tri.z};
    cells->InsertNextCell(3, ids);
    const Material& m = scene.material_of(t);
    // The albedo as the surface colour (with the vertex colour at the
    // triangle's centre); a lamp shows its emission's hue.
    const glm::vec3 centre = (scene.vertex(t, 0) + scene.vertex(t, 1) + scene.vertex(t, 2)) / 3.0f;
    glm::vec3 c = m.is_emissive()
                      ? m.emission / std::max({m.emission.r, m.emission.g, m.emission.b})
                      : scene.flat_albedo_at(t, centre);
    c = glm::clamp(c, 0.0f, 1.0f) * 255.0f;
    colours->InsertNextTuple3(c.r, c.g, c.b);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cells);
  poly->GetCellData()->SetScalars(colours);
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(poly);
  mapper->SetScalarModeToUseCellData();
  mapper->SetColorModeToDirectScalars();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  // Walls of a closed room face inwards; show both sides alike.
  actor->GetProperty()->BackfaceCullingOff();
  // The headlight grazes the side walls of a room: ambient keeps their colour readable.
  actor->GetProperty()->SetAmbient(0.45);
  actor->GetProperty()->SetDiffuse(0.6);
  return actor;
}

void apply_scene_camera(const Scene& scene, vtkRenderer& renderer) {
  vtkCamera* camera = renderer.GetActiveCamera();
  const Camera& c = scene.camera;
  camera->SetPosition(c.position.x, c.position.y, c.position.z);
  camera->SetFocalPoint(c.target.x, c.target.y, c.target.z);
  camera->SetViewUp(c.up.x, c.up.y, c.up.z);
  camera->SetViewAngle(c.fov_y_deg);
  renderer.ResetCameraClippingRange();
}

}  // namespace bounce::views
