#pragma once
// Public: load a scene (docs/scene-format.md): a scene folder, its
// scene.json or a bare mesh file. Problems the loader repairs are reported
// to the Diagnostics; anything it cannot read throws bounce::Error naming
// the file.
//
//   bounce::Diagnostics diagnostics;
//   const bounce::Scene scene = bounce::SceneLoader(diagnostics).load(path);
//
// A scene's materials keep their decoded textures (linear MIP levels) and
// alpha masks, and any surface point has texture coordinates, so a viewer
// can draw the surfaces as the bake saw them.
#include "base/diagnostics.h"
#include "base/error.h"
#include "scene/alpha_mask.h"
#include "scene/scene.h"
#include "scene/scene_loader.h"
#include "scene/surface_texture.h"
#include "scene/texture.h"
