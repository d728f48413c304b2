#pragma once
// Loader tests on files written out for them: an OBJ file of one unit quad
// in z = 0 facing +z, texture coordinates (x, y), one material "quad" whose
// Kd and further MTL lines the test gives, in a scratch folder with the
// diagnostics of its load.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "base/diagnostics.h"
#include "scene/scene_loader.h"
#include "scratch_dir.h"

namespace bounce::test {

class QuadFiles : public ::testing::Test {
 protected:
  ScratchDir dir{"bounce-quad-files"};
  Diagnostics diagnostics;

  void write(const std::string& name, const std::string& bytes) {
    std::ofstream(dir / name, std::ios::binary) << bytes;
  }
  // Writes quad.obj and quad.mtl (`material_lines` after "Kd <kd>") and
  // loads the OBJ.
  Scene load_obj_quad(const std::string& material_lines, const std::string& kd = "0.5 0.5 0.5") {
    write("quad.mtl", "newmtl quad\nKd " + kd + "\n" + material_lines + "\n");
    write("quad.obj",
          "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
          "usemtl quad\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
    return SceneLoader(diagnostics).load(dir / "quad.obj");
  }
};

}  // namespace bounce::test
