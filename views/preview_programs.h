#pragma once
// The live preview's shader programs (views/preview_widget.h lists the
// passes), compiled and linked from the shaders built into the studio
// (shaders/, embedded by CMake), so the studio runs from any folder.
#include <memory>

#include <QOpenGLShaderProgram>

namespace bounce::views {

struct PreviewPrograms {
  std::unique_ptr<QOpenGLShaderProgram> shadow, gbuffer, shape, ssao, blur, composite;

  // Needs a current OpenGL 3.3 context. Throws bounce::Error naming the
  // shader (and the driver's log) when one does not compile or link.
  static PreviewPrograms build();
};

}  // namespace bounce::views
