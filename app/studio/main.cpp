// bounce-studio: the desktop editor, or (with --screenshot) one view rendered
// to a PNG without user interaction.
#include <cstdio>

#include <QVTKOpenGLNativeWidget.h>
#include <QApplication>
#include <QCommandLineParser>
#include <QSurfaceFormat>

#include "base/error.h"
#include "headless.h"
#include "main_window.h"
#include "vtk_error_capture.h"

int main(int argc, char** argv) {
  // VTK needs its OpenGL context format before any widget exists.
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  QApplication::setOrganizationName("Bounce");
  QApplication::setApplicationName("Bounce Studio");
  QApplication::setApplicationVersion(BOUNCE_VERSION);
  bounce::views::VtkErrorCapture::install();

  QCommandLineParser parser;
  parser.setApplicationDescription(
      "Bounce Studio: bake a scene and look at its voxels, patches and transport matrix.");
  parser.addHelpOption();
  parser.addVersionOption();
  parser.addPositionalArgument("input", "Scene (folder, scene.json or mesh) or bake folder");
  const QCommandLineOption screenshot("screenshot", "Render one view to this PNG and exit.",
                                      "out.png");
  const QCommandLineOption view("view", "View for --screenshot: voxels, patches, matrix or error.",
                                "view", "voxels");
  const QCommandLineOption size("size", "Picture size for --screenshot, WxH.", "WxH", "1024x768");
  const QCommandLineOption voxel("voxel", "Bake with this many voxels along the longest side.",
                                 "N");
  const QCommandLineOption patches_total("patches-total", "Bake for about this many patches.", "N");
  const QCommandLineOption codec("codec", "Matrix storage: auto, dense, paper or ours.", "codec");
  const QCommandLineOption bake_out("bake-out", "Keep the bake folder of --screenshot here.",
                                    "dir");
  const QCommandLineOption pick("pick-patch", "Patches view: pick this patch, as a click would.",
                                "index");
  parser.addOptions({screenshot, view, size, voxel, patches_total, codec, bake_out, pick});
  parser.process(app);
  const QStringList inputs = parser.positionalArguments();

  auto integer = [&](const QCommandLineOption& option, int fallback) {
    if (!parser.isSet(option)) return fallback;
    bool ok = false;
    const int v = parser.value(option).toInt(&ok);
    if (!ok || v < 0)
      throw bounce::Error(
          "--" + option.names().front().toStdString(),
          "must be a whole number >= 0, got '" + parser.value(option).toStdString() + "'");
    return v;
  };

  try {
    if (parser.isSet(screenshot)) {
      if (inputs.size() != 1)
        throw bounce::Error("--screenshot", "needs exactly one scene or bake folder");
      if (parser.isSet(voxel) && parser.isSet(patches_total))
        throw bounce::Error("--patches-total", "cannot be combined with --voxel");
      bounce::studio::ScreenshotRequest r;
      r.input = inputs.front();
      r.screenshot = parser.value(screenshot);
      r.view = parser.value(view);
      const QStringList wh = parser.value(size).split('x');
      bool ok_w = false, ok_h = false;
      if (wh.size() == 2) {
        r.width = wh[0].toInt(&ok_w);
        r.height = wh[1].toInt(&ok_h);
      }
      if (!ok_w || !ok_h)
        throw bounce::Error(
            "--size", "must be WxH, e.g. 1024x768, got '" + parser.value(size).toStdString() + "'");
      r.voxel = integer(voxel, 0);
      r.patches_total = integer(patches_total, 0);
      r.codec = parser.value(codec);
      r.bake_out = parser.value(bake_out);
      r.pick_patch = integer(pick, -1);
      bounce::studio::take_screenshot(r);
      return 0;
    }
    bounce::studio::MainWindow window;
    window.resize(1400, 900);
    window.show();
    if (!inputs.isEmpty()) window.open(inputs.front());
    return QApplication::exec();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bounce-studio: error: %s\n", e.what());
    return 1;
  }
}
