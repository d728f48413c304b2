// bounce-studio: the desktop editor, or (with --screenshot) one view rendered
// to a PNG without user interaction.
#include <cstdio>

#include <QVTKOpenGLNativeWidget.h>
#include <QApplication>
#include <QCommandLineParser>
#include <QSurfaceFormat>

#include "bounce/blas.h"
#include "bounce/error.h"
#include "headless.h"
#include "main_window.h"
#include "screenshot_options.h"
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
  const bounce::studio::ScreenshotOptions screenshot;
  screenshot.add_to(parser);
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

  try {
    if (screenshot.requested(parser)) {
      bounce::studio::take_screenshot(screenshot.read(parser, inputs));
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
