#pragma once
// A small Cornell box baked with the compressed matrix and the exact T.npy
// (--dump-matrices), written and read back as a front end opens it: the bake
// the studio's views show, for tests of the core functions they call.
#include <string>

#include "bake/bake.h"
#include "bake/bake_writer.h"
#include "folder/bake_reader.h"
#include "scene/scene_loader.h"
#include "scratch_dir.h"

namespace bounce::test {

inline const LoadedBake& compressed_cornell_bake() {
  struct Fixture {
    ScratchDir dir{"bounce-compressed-cornell"};
    LoadedBake loaded;
    Fixture() {
      Diagnostics d;
      const Scene scene =
          SceneLoader(d).load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-box");
      BakeSettings s;
      s.voxel_resolution = 4;
      s.codec = CodecChoice::LightWeighted;
      s.dump_matrices = true;
      s.pictures = false;
      Progress progress;
      const BakeResult bake = Baker(scene, s, d).run(progress);
      write_bake(dir / "bake", scene, bake, d);
      loaded = BakeReader::read(dir / "bake", BakeReader::Dense::kRead);
    }
  };
  static const Fixture f;
  return f.loaded;
}

}  // namespace bounce::test
