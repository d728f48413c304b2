# Every dependency comes from a Debian 12 package (see tools/packages.txt).
# Packaging quirks of this distribution are handled here, in one place.
find_package(PkgConfig REQUIRED)
find_package(OpenMP REQUIRED)
find_package(Threads REQUIRED)
find_package(embree 3 REQUIRED)
find_package(assimp REQUIRED)
find_package(glm REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
# OpenImageIO's CMake config is broken on Debian 12 (it references
# /usr/bin/iconvert and /usr/include/opencv4): use its pkg-config file.
pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
