// The render tests' main: a QApplication (views are widgets) with VTK's
// messages captured, then GoogleTest.
#include <gtest/gtest.h>

#include <QVTKOpenGLNativeWidget.h>
#include <QApplication>
#include <QSurfaceFormat>

#include "vtk_error_capture.h"

int main(int argc, char** argv) {
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  bounce::views::VtkErrorCapture::install();
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
