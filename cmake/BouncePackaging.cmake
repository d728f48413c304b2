# `cpack -G DEB` in the build folder: bounce_<version>_amd64.deb, everything
# `cmake --install` installs (cmake/BounceInstall.cmake) under /usr, for
# Debian 12 (docs/install.md: `apt install ./bounce_*.deb`).
#
# The run-time dependencies are Debian package names: dpkg-shlibdeps finds
# the package of every shared library the programs and the Python module
# link, and the list below adds what they load or read at run time without
# linking it (an OpenCL platform, the label font, numpy for the module). The
# static libraries and headers are in the package too; building against them
# needs the -dev packages of tools/packages.txt, as building Bounce does.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME bounce)
set(CPACK_PACKAGE_VENDOR "Bounce")
set(CPACK_PACKAGE_CONTACT "Bounce developers <bounce@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Precomputed radiosity with virtual patches: baker, studio, runtime")
set(CPACK_PACKAGE_DESCRIPTION
    "Bounce bakes precomputed radiosity with virtual patches into a compressed transport matrix that a renderer multiplies by its direct light each frame. The package holds the command-line baker `bounce`, Bounce Studio, the Python module `bounce`, the runtime and core static libraries with their headers and CMake package, and example scenes.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "fonts-dejavu-core, pocl-opencl-icd | opencl-icd")
# The Python module is built for one Python minor version (its file name says
# which, e.g. cpython-311) and imports numpy.
if(BOUNCE_PYTHON_ENABLED)
  math(EXPR python_next_minor "${Python3_VERSION_MINOR} + 1")
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS
         ", python3 (>= ${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}~)"
         ", python3 (<< ${Python3_VERSION_MAJOR}.${python_next_minor}), python3-numpy")
endif()
include(CPack)
