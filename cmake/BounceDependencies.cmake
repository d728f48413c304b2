# Every dependency comes from a Debian 12 package (see tools/packages.txt).
# Packaging quirks of this distribution are handled here, in one place.
find_package(PkgConfig REQUIRED)
find_package(OpenMP REQUIRED)
find_package(Threads REQUIRED)
find_package(embree 3 REQUIRED)
find_package(assimp REQUIRED)
# OpenMesh 9 (core/runtime/mesh_transfer): Debian 12 ships a CMake config
# exporting OpenMeshCore/OpenMeshTools for configuration "None" only and no
# version file, so ask for the config without a version; CMake falls back to
# the one imported configuration for Release and Debug.
find_package(OpenMesh REQUIRED CONFIG)
find_package(glm REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
# OpenImageIO's CMake config is broken on Debian 12 (it references
# /usr/bin/iconvert and /usr/include/opencv4): use its pkg-config file.
pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
# Dense linear algebra (core/transport): OpenBLAS for BLAS and LAPACK (its
# headers live in an arch- and threading-specific folder: ask pkg-config),
# LAPACKE for the C interface, CLBlast on OpenCL (PoCL's CPU device here).
pkg_check_modules(OPENBLAS REQUIRED IMPORTED_TARGET openblas)
find_library(LAPACKE_LIBRARY lapacke REQUIRED)
find_package(OpenCL REQUIRED)
find_package(CLBlast REQUIRED)
# Block compression baselines (core/compress): libsquish's pkg-config file is
# broken on Debian 12, find the library directly; stb_dxt is header-only.
find_library(SQUISH_LIB squish REQUIRED)
find_path(STB_INCLUDE_DIR stb/stb_dxt.h REQUIRED)
# Distributed bake (core/distributed, docs/cluster.md): OpenMPI and
# ScaLAPACK built against it (libscalapack-openmpi-dev, whose CMake config is
# for configuration "None" only: find the library itself). Built by default
# when both are installed; `bounce bake` under mpirun then shares the bake.
option(BOUNCE_MPI "Distributed bake with MPI and ScaLAPACK (needs openmpi and scalapack)" ON)
set(BOUNCE_MPI_ENABLED OFF)
if(BOUNCE_MPI)
  find_package(MPI COMPONENTS C QUIET)
  find_library(SCALAPACK_LIBRARY NAMES scalapack-openmpi scalapack)
  if(MPI_C_FOUND AND SCALAPACK_LIBRARY)
    set(BOUNCE_MPI_ENABLED ON)
  else()
    message(WARNING "Distributed bake skipped: MPI or ScaLAPACK not found; install openmpi-bin "
                    "libopenmpi-dev libscalapack-openmpi-dev")
  endif()
endif()
# Bounce Studio (views/, app/studio/, tests/render/): Qt 5 Widgets and VTK 9.
# VTK 9.1 on Debian 12 is built against Qt 5 and MPI: its config needs
# MPI::MPI_C to exist, so MPI (C only) is found first. The studio is skipped,
# with a warning, only when the packages are missing; the core never links them.
option(BOUNCE_STUDIO "Build Bounce Studio (needs Qt 5 and VTK 9, see tools/packages.txt)" ON)
set(BOUNCE_STUDIO_ENABLED OFF)
if(BOUNCE_STUDIO)
  find_package(Qt5 COMPONENTS Widgets QUIET)
  find_package(MPI COMPONENTS C QUIET)
  if(Qt5_FOUND AND MPI_C_FOUND)
    find_package(VTK QUIET COMPONENTS CommonCore CommonDataModel FiltersCore FiltersSources
                 FiltersGeneral GUISupportQt InteractionStyle RenderingCore RenderingOpenGL2
                 RenderingAnnotation RenderingFreeType ChartsCore ViewsContext2D
                 RenderingContext2D RenderingContextOpenGL2 IOImage)
  endif()
  if(Qt5_FOUND AND VTK_FOUND)
    set(BOUNCE_STUDIO_ENABLED ON)
  else()
    message(WARNING "Bounce Studio skipped: Qt 5 Widgets or VTK 9 (with MPI C) not found; "
                    "install qtbase5-dev libqt5opengl5-dev libvtk9-qt-dev libvtk9-dev")
  endif()
endif()
