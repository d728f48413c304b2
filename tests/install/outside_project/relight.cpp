// relight BAKE LIGHT X Y Z OUT: opens BAKE and the scene it was made from,
// moves the light called LIGHT to (X, Y, Z), lights one frame and writes
// E, b and T b per patch to OUT, as `bounce solve --float32 --light` does.
#include <cstdio>
#include <cstdlib>

#include <bounce/bake_folder.h>
#include <bounce/relight.h>

int main(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr, "usage: relight BAKE LIGHT X Y Z OUT\n");
    return 2;
  }
  try {
    bounce::LightingSessionSettings settings;
    settings.relighter.loop = bounce::CppLoop::kFloat32;
    settings.relighter.frame.publish = false;
    bounce::LightingSession session(argv[1], settings);
    session.move_light(argv[2], {std::atof(argv[3]), std::atof(argv[4]), std::atof(argv[5])});
    session.light();
    const std::size_t n = session.bake().size();
    bounce::write_npy(argv[6], session.frame().record(), {n, 3, 3});
    std::printf("%zu patches lit with %s\n", n, session.relighter().multiply_name().c_str());
  } catch (const bounce::Error& e) {
    std::fprintf(stderr, "relight: %s\n", e.what());
    return 1;
  }
  return 0;
}
