#include "vtk_error_capture.h"

#include <cstdio>
#include <mutex>

#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

namespace bounce::views {

namespace {

std::mutex g_mutex;
std::vector<std::string> g_messages;

class CapturingOutputWindow : public vtkOutputWindow {
 public:
  static CapturingOutputWindow* New();
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow)

      void DisplayText(const char* text) override {
    std::fputs(text, stderr);
  }
  void DisplayErrorText(const char* text) override { record("VTK error: ", text); }
  void DisplayWarningText(const char* text) override { record("VTK warning: ", text); }
  void DisplayGenericWarningText(const char* text) override { record("VTK warning: ", text); }

 private:
  static void record(const char* kind, const char* text) {
    std::fprintf(stderr, "%s%s\n", kind, text);
    std::lock_guard lock(g_mutex);
    g_messages.push_back(std::string(kind) + text);
  }
};

vtkStandardNewMacro(CapturingOutputWindow);

}  // namespace

void VtkErrorCapture::install() {
  static const bool installed = [] {
    vtkSmartPointer<CapturingOutputWindow> window = vtkSmartPointer<CapturingOutputWindow>::New();
    vtkOutputWindow::SetInstance(window);
    return true;
  }();
  (void)installed;
}

std::vector<std::string> VtkErrorCapture::messages() {
  std::lock_guard lock(g_mutex);
  return g_messages;
}

void VtkErrorCapture::clear() {
  std::lock_guard lock(g_mutex);
  g_messages.clear();
}

}  // namespace bounce::views
