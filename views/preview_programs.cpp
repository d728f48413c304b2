#include "preview_programs.h"

#include <cstring>
#include <string>

#include "bounce/error.h"
#include "views/embedded_shaders.h"

namespace bounce::views {

namespace {

const char* shader_source(const char* name) {
  for (const EmbeddedShader& s : kEmbeddedShaders)
    if (std::strcmp(s.name, name) == 0) return s.source;
  throw Error(std::string("shaders/") + name, "not built into the studio (rerun CMake)");
}

std::unique_ptr<QOpenGLShaderProgram> link(const char* vert, const char* frag) {
  auto p = std::make_unique<QOpenGLShaderProgram>();
  if (!p->addShaderFromSourceCode(QOpenGLShader::Vertex, shader_source(vert)))
    throw Error(std::string("shaders/") + vert, p->log().toStdString());
  if (!p->addShaderFromSourceCode(QOpenGLShader::Fragment, shader_source(frag)))
    throw Error(std::string("shaders/") + frag, p->log().toStdString());
  if (!p->link())
    throw Error(std::string("shaders/") + vert + " + " + frag, p->log().toStdString());
  return p;
}

}  // namespace

PreviewPrograms PreviewPrograms::build() {
  PreviewPrograms p;
  p.shadow = link("preview_shadow.vert", "preview_shadow.frag");
  p.gbuffer = link("preview_gbuffer.vert", "preview_gbuffer.frag");
  p.shape = link("preview_shape.vert", "preview_shape.frag");
  p.ssao = link("preview_fullscreen.vert", "preview_ssao.frag");
  p.blur = link("preview_fullscreen.vert", "preview_blur.frag");
  p.composite = link("preview_fullscreen.vert", "preview_composite.frag");
  return p;
}

}  // namespace bounce::views
