#pragma once
// Catches VTK's error and warning messages instead of letting them scroll by:
// a render that printed "ERROR: In vtkOpenGL..." is a failed render even when
// a picture came out (the same rule 3D Slicer's tests apply through its
// vtkOutputWindow hook). Messages still go to stderr.
#include <string>
#include <vector>

namespace bounce::views {

class VtkErrorCapture {
 public:
  // Installs the capturing output window for the whole process (idempotent).
  static void install();
  // Errors and warnings seen since install() or the last clear().
  static std::vector<std::string> messages();
  static void clear();
};

}  // namespace bounce::views
