#pragma once
// The scene in VTK, shared by the 3D views: its triangles as one actor and
// its camera on a vtkCamera.
#include <vtkSmartPointer.h>

#include "bounce/scene.h"

class vtkActor;
class vtkRenderer;

namespace bounce::views {

// Flat grey triangles of the whole scene (emissive materials in their light
// colour so the lamp is recognisable).
vtkSmartPointer<vtkActor> make_scene_mesh_actor(const Scene& scene);

// Points the renderer's camera like the scene's own camera, then resets the
// clipping range to what is visible.
void apply_scene_camera(const Scene& scene, vtkRenderer& renderer);

}  // namespace bounce::views
