#pragma once
// Light and camera for scenes that do not give their own (a bare mesh file;
// a scene.json without `camera`), derived from the scene's bounding box so a
// model in any unit is lit and framed alike. Documented in
// docs/scene-format.md ("Bare mesh files"). Internal to the scene module.
#include "scene/scene.h"

namespace bounce::scene_internal {

// Field of view of the derived camera, in degrees (vertical).
inline constexpr float kDefaultFovYDeg = 45.0f;

// One white point light above the centre of the bounds, at 80% of their
// height, with intensity (W/sr) = squared diagonal: the irradiance it gives
// one diagonal away is 1 W/m^2, whatever the model's units.
Light default_light(const Bounds& bounds);

// Looks at the centre of the bounds from +z, far enough that the bounding
// sphere fits the vertical field of view.
Camera default_camera(const Bounds& bounds);

}  // namespace bounce::scene_internal
