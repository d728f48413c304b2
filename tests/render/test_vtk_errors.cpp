#include <vtkOutputWindow.h>

#include "render_support.h"

namespace bounce::render_test {

// The hook every render test relies on: VTK's messages land in the capture.
TEST(VtkErrors, AreCaptured) {
  views::VtkErrorCapture::clear();
  vtkOutputWindow::GetInstance()->DisplayErrorText("render test: induced error");
  vtkOutputWindow::GetInstance()->DisplayWarningText("render test: induced warning");
  const std::vector<std::string> messages = views::VtkErrorCapture::messages();
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_NE(messages[0].find("induced error"), std::string::npos);
  EXPECT_NE(messages[1].find("induced warning"), std::string::npos);
  views::VtkErrorCapture::clear();
}

}  // namespace bounce::render_test
