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
# BOUNCE_REQUIRE_ALL=ON (./dev.sh test, CI): the optional parts below must
# all be built. Without it a missing package only drops its part (with a
# warning), and the tests of that part vanish from ctest without failing
# anything; with it, configuring fails and names each missing component.
option(BOUNCE_REQUIRE_ALL "Fail configuring unless the studio (Qt 5, VTK), the distributed bake (MPI, ScaLAPACK) and the Python module (pybind11) can be built" OFF)
set(BOUNCE_MISSING_COMPONENTS "")
# Turns `flag` ON when the list `missing` is empty; else warns that `part` is
# skipped, naming every missing component, and records them. A macro, so
# that both variables are set in the caller's scope.
macro(bounce_enable_unless_missing part flag)
  if(missing)
    list(JOIN missing ", " missing_text)
    message(WARNING "${part} skipped, not found: ${missing_text}")
    list(APPEND BOUNCE_MISSING_COMPONENTS ${missing})
  else()
    set(${flag} ON)
  endif()
endmacro()

# Distributed bake (core/distributed, docs/cluster.md): OpenMPI and
# ScaLAPACK built against it (libscalapack-openmpi-dev, whose CMake config is
# for configuration "None" only: find the library itself). Built by default
# when both are installed; `bounce bake` under mpirun then shares the bake.
option(BOUNCE_MPI "Distributed bake with MPI and ScaLAPACK (needs openmpi and scalapack)" ON)
set(BOUNCE_MPI_ENABLED OFF)
if(BOUNCE_MPI)
  find_package(MPI COMPONENTS C QUIET)
  find_library(SCALAPACK_LIBRARY NAMES scalapack-openmpi scalapack)
  set(missing "")
  if(NOT MPI_C_FOUND)
    list(APPEND missing "MPI for C (libopenmpi-dev, openmpi-bin)")
  endif()
  if(NOT SCALAPACK_LIBRARY)
    list(APPEND missing "ScaLAPACK (libscalapack-openmpi-dev)")
  endif()
  bounce_enable_unless_missing("Distributed bake" BOUNCE_MPI_ENABLED)
elseif(BOUNCE_REQUIRE_ALL)
  list(APPEND BOUNCE_MISSING_COMPONENTS "the distributed bake (BOUNCE_MPI is OFF)")
endif()
# Bounce Studio (views/, app/studio/, tests/render/): Qt 5 Widgets and VTK 9.
# VTK 9.1 on Debian 12 is built against Qt 5 and MPI: its config needs
# MPI::MPI_C to exist, so MPI (C only) is found first. The studio is skipped,
# with a warning naming what is missing, only when packages are missing; the
# core never links them.
option(BOUNCE_STUDIO "Build Bounce Studio (needs Qt 5 and VTK 9, see tools/packages.txt)" ON)
set(BOUNCE_STUDIO_ENABLED OFF)
set(BOUNCE_VTK_MODULES CommonCore CommonDataModel FiltersCore FiltersSources FiltersGeneral
    GUISupportQt InteractionStyle RenderingCore RenderingOpenGL2 RenderingAnnotation
    RenderingFreeType ChartsCore ViewsContext2D RenderingContext2D RenderingContextOpenGL2 IOImage)
if(BOUNCE_STUDIO)
  find_package(Qt5 COMPONENTS Widgets QUIET)
  find_package(MPI COMPONENTS C QUIET)
  set(missing "")
  if(NOT Qt5_FOUND)
    list(APPEND missing "Qt 5 Widgets (qtbase5-dev)")
  endif()
  if(NOT MPI_C_FOUND)
    list(APPEND missing "MPI for C, which VTK 9 needs (libopenmpi-dev)")
  else()
    # Each module on its own: VTK_FOUND alone cannot say which one is missing.
    find_package(VTK QUIET COMPONENTS ${BOUNCE_VTK_MODULES})
    if(NOT VTK_VERSION)
      list(APPEND missing "VTK 9 (libvtk9-dev)")
    else()
      foreach(module ${BOUNCE_VTK_MODULES})
        if(NOT VTK_${module}_FOUND)
          list(APPEND missing "VTK module ${module}")
        endif()
      endforeach()
      if(NOT VTK_FOUND AND NOT missing)
        list(APPEND missing "VTK 9: ${VTK_NOT_FOUND_MESSAGE}")
      endif()
    endif()
  endif()
  bounce_enable_unless_missing("Bounce Studio" BOUNCE_STUDIO_ENABLED)
elseif(BOUNCE_REQUIRE_ALL)
  list(APPEND BOUNCE_MISSING_COMPONENTS "Bounce Studio (BOUNCE_STUDIO is OFF)")
endif()

# The Python module (python/, docs/python.md): pybind11 and the Python
# headers. Built by default when both are installed.
option(BOUNCE_PYTHON "Build the Python module `bounce` (needs pybind11-dev and python3-dev)" ON)
set(BOUNCE_PYTHON_ENABLED OFF)
if(BOUNCE_PYTHON)
  # The distribution's interpreter, whose packages (python3-numpy) the tests
  # use, rather than one found first on PATH (pyenv, a virtualenv); give
  # -DPython3_EXECUTABLE=... for another.
  if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3)
  endif()
  find_package(Python3 COMPONENTS Interpreter Development.Module QUIET)
  set(missing "")
  if(NOT Python3_Development.Module_FOUND)
    list(APPEND missing "Python 3 headers (python3-dev)")
  else()
    # pybind11's own config finds Python through FindPython, as above.
    set(PYBIND11_FINDPYTHON ON)
    find_package(pybind11 2.10 CONFIG QUIET)
    if(NOT pybind11_FOUND)
      list(APPEND missing "pybind11 (pybind11-dev)")
    endif()
  endif()
  bounce_enable_unless_missing("The Python module" BOUNCE_PYTHON_ENABLED)
elseif(BOUNCE_REQUIRE_ALL)
  list(APPEND BOUNCE_MISSING_COMPONENTS "the Python module (BOUNCE_PYTHON is OFF)")
endif()

if(BOUNCE_REQUIRE_ALL AND BOUNCE_MISSING_COMPONENTS)
  list(REMOVE_DUPLICATES BOUNCE_MISSING_COMPONENTS)
  list(JOIN BOUNCE_MISSING_COMPONENTS "\n  " missing_text)
  message(FATAL_ERROR "BOUNCE_REQUIRE_ALL is ON and these are missing:\n  ${missing_text}\n"
                      "Install them (tools/packages.txt) or configure with "
                      "-DBOUNCE_REQUIRE_ALL=OFF to build without them.")
endif()
