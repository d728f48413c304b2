// bounce-studio: the desktop editor, or (with --screenshot) one view rendered
// to a PNG without user interaction.
#include <cmath>
#include <cstdio>

#include <QVTKOpenGLNativeWidget.h>
#include <QApplication>
#include <QCommandLineParser>
#include <QSurfaceFormat>

#include "bounce/blas.h"
#include "bounce/error.h"
#include "headless.h"
#include "main_window.h"
#include "vtk_error_capture.h"

namespace {

void name_application() {
  QCoreApplication::setOrganizationName("Bounce");
  QCoreApplication::setApplicationName("Bounce Studio");
  QCoreApplication::setApplicationVersion(BOUNCE_VERSION);
}

// QApplication aborts without a display, before the options are parsed; help
// and version need none, so they are answered by a QCoreApplication first.
bool asks_for_help_or_version(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const QString a = QString::fromLocal8Bit(argv[k]);
    if (a == "--") break;
    if (a == "-h" || a == "--help" || a == "-?" || a == "--help-all" || a == "-v" ||
        a == "--version")
      return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  // Before a bake's worker thread or the preview runs BLAS.
  bounce::choose_blas_kernels();
  QCommandLineParser parser;
  parser.setApplicationDescription(
      "Bounce Studio: bake a scene and look at its voxels, patches and transport matrix.");
  parser.addHelpOption();
  parser.addVersionOption();
  parser.addPositionalArgument("input", "Scene (folder, scene.json or mesh) or bake folder");
  const QCommandLineOption screenshot("screenshot", "Render one view to this PNG and exit.",
                                      "out.png");
  const QCommandLineOption view(
      "view", "View for --screenshot: voxels, patches, matrix, error, preview or report.", "view",
      "voxels");
  const QCommandLineOption size("size", "Picture size for --screenshot, WxH.", "WxH", "1024x768");
  const QCommandLineOption voxel("voxel", "Bake with this many voxels along the longest side.",
                                 "N");
  const QCommandLineOption patches_total("patches-total", "Bake for about this many patches.", "N");
  const QCommandLineOption codec("codec", "Matrix storage: auto, dense, paper or ours.", "codec");
  const QCommandLineOption size_limit(
      "size-limit",
      "Largest compressed matrix the error budget's search may give, as a share of dense.", "F");
  const QCommandLineOption bake_out("bake-out", "Keep the bake folder of --screenshot here.",
                                    "dir");
  const QCommandLineOption pick("pick-patch", "Patches view: pick this patch, as a click would.",
                                "index");
  const QCommandLineOption light("light", "Preview view: move the scene's light to x,y,z first.",
                                 "x,y,z");
  const QCommandLineOption report(
      "report", "Report view: show this report.json (default: run the quick sweep on the scene).",
      "report.json");
  const QCommandLineOption passes(
      "passes", "Preview view: the passes to show, any of direct,indirect,ao (default: all).",
      "list");
  const QCommandLineOption compare_codec(
      "compare-codec", "Error view: re-compress the bake with paper or ours and show that.",
      "codec");
  parser.addOptions({screenshot, view, size, voxel, patches_total, codec, size_limit, bake_out,
                     pick, light, report, passes, compare_codec});
  if (asks_for_help_or_version(argc, argv)) {
    QCoreApplication core(argc, argv);
    name_application();
    parser.process(core);  // prints the help or version and exits 0
    return 0;
  }
  // VTK needs its OpenGL context format before any widget exists.
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  name_application();
  bounce::views::VtkErrorCapture::install();
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
      r.size_limit = parser.value(size_limit);
      r.bake_out = parser.value(bake_out);
      r.pick_patch = integer(pick, -1);
      r.compare_codec = parser.value(compare_codec);
      r.report = parser.value(report);
      r.passes = parser.value(passes);
      if (parser.isSet(light)) {
        const QStringList xyz = parser.value(light).split(',');
        bool ok = xyz.size() == 3;
        float* coordinate[3] = {&r.light_x, &r.light_y, &r.light_z};
        for (int k = 0; ok && k < 3; ++k) {
          *coordinate[k] = xyz[k].toFloat(&ok);
          ok = ok && std::isfinite(*coordinate[k]);
        }
        if (!ok)
          throw bounce::Error("--light", "must be x,y,z (three numbers), got '" +
                                             parser.value(light).toStdString() + "'");
        r.has_light = true;
      }
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
