#pragma once
// `bounce-studio SCENE|BAKE --screenshot out.png --view voxels|patches|matrix|error`:
// loads (baking a scene first, with the settings panel's mapping of the
// options given), renders one view at the requested size into a PNG and
// returns the exit code. Used by the render tests and for the README pictures.
#include <QImage>
#include <QString>

namespace bounce::studio {

struct ScreenshotRequest {
  QString input;       // scene or bake folder
  QString screenshot;  // PNG to write
  QString view;        // voxels, patches, matrix, error, preview
  int width = 1024, height = 768;
  int voxel = 0;           // > 0: --voxel
  int patches_total = 0;   // > 0: --patches-total
  QString codec;           // empty: the panel's default
  QString size_limit;      // empty: the panel's default
  QString bake_out;        // keep the bake folder here (default: a temporary one)
  int pick_patch = -1;     // patches view: pick this patch, as a click would
  QString compare_codec;   // error view: re-compress with paper or ours (empty: as baked)
  QString report;          // report view: show this report.json (default: run the quick sweep)
  QString passes;          // preview view: comma-separated direct, indirect, ao (empty: all)
  bool has_light = false;  // preview view: move the light to (light_x, light_y, light_z)
  float light_x = 0.0f, light_y = 0.0f, light_z = 0.0f;
  bool probes = false;      // preview view: draw the light probes (a bake with them)
  bool has_sphere = false;  // preview view: the probe-lit sphere at (sphere_x, ...)
  float sphere_x = 0.0f, sphere_y = 0.0f, sphere_z = 0.0f;
  QString object;  // preview view: this mesh as the probe-lit object (empty: the sphere)
};

// Throws bounce::Error for bad requests and failed bakes or renders.
void take_screenshot(const ScreenshotRequest& request);

// Writes a rendered view to `path` as PNG (atomically, QSaveFile) after
// checking that VTK reported no error while rendering it; throws bounce::Error.
void save_view_png(const QImage& image, const QString& path);

}  // namespace bounce::studio
