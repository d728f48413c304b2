// The render tests' main: a QApplication (views are widgets) with VTK's
// messages captured, then GoogleTest. A fatal signal prints the stack before
// the process ends: a crash under CI's Xvfb and llvmpipe then says where it
// happened, which a rerun on another machine may not reproduce.
#include <execinfo.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>

#include <QVTKOpenGLNativeWidget.h>
#include <QApplication>
#include <QSurfaceFormat>

#include "vtk_error_capture.h"

namespace {

// Only async-signal-safe calls: write, backtrace_symbols_fd, signal, raise.
// (backtrace() is loaded before the handler is installed, so it does not
// allocate here.)
void print_stack_and_die(int signal_number) {
  constexpr char kHeader[] = "\n*** fatal signal in the render tests; stack:\n";
  [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, kHeader, sizeof kHeader - 1);
  void* frames[64];
  const int count = backtrace(frames, 64);
  backtrace_symbols_fd(frames, count, STDERR_FILENO);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

void print_stack_on_fatal_signals() {
  void* warm_up[1];
  backtrace(warm_up, 1);
  for (const int s : {SIGABRT, SIGSEGV, SIGBUS, SIGILL, SIGFPE})
    std::signal(s, print_stack_and_die);
}

}  // namespace

int main(int argc, char** argv) {
  print_stack_on_fatal_signals();
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  bounce::views::VtkErrorCapture::install();
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
