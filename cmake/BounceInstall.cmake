# What `cmake --install` puts under the prefix (docs/install.md), by
# component: `cli` (bounce), `studio` (bounce-studio, its .desktop entry and
# icon), `development` (the static libraries Bounce::runtime and Bounce::core,
# the headers, the CMake package), `python` (python/CMakeLists.txt), `data`
# (the example scenes) and `licences` (the scenes' credits). Nothing installed
# refers back to the source or build tree: the OpenCL kernels and the studio's
# shaders are compiled into the programs.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(BOUNCE_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/Bounce)
set(BOUNCE_INSTALL_DOCDIR ${CMAKE_INSTALL_DATAROOTDIR}/doc/bounce)

install(TARGETS bounce RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT cli)
if(BOUNCE_STUDIO_ENABLED)
  install(TARGETS bounce-studio RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT studio)
  install(FILES ${PROJECT_SOURCE_DIR}/resources/studio/bounce-studio.desktop
          DESTINATION ${CMAKE_INSTALL_DATADIR}/applications COMPONENT studio)
  install(FILES ${PROJECT_SOURCE_DIR}/resources/studio/bounce-studio.svg
          DESTINATION ${CMAKE_INSTALL_DATADIR}/icons/hicolor/scalable/apps COMPONENT studio)
endif()

# The libraries, exported as Bounce::runtime and Bounce::core.
install(TARGETS bounce_runtime bounce_core EXPORT BounceTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development)
install(EXPORT BounceTargets NAMESPACE Bounce:: DESTINATION ${BOUNCE_INSTALL_CMAKEDIR}
        COMPONENT development)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/BounceConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/BounceConfig.cmake
                              INSTALL_DESTINATION ${BOUNCE_INSTALL_CMAKEDIR})
# 0.x: a minor version may change the API, so only the same minor matches.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/BounceConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/BounceConfig.cmake ${PROJECT_BINARY_DIR}/BounceConfigVersion.cmake
        DESTINATION ${BOUNCE_INSTALL_CMAKEDIR} COMPONENT development)

# Headers: the public ones (core/bounce/) as <prefix>/include/bounce/NAME.h,
# and the module headers they include, as the source tree has them, under
# <prefix>/include/bounce/core/ (both folders are on Bounce::runtime's
# include path). The distributed bake's header needs bounce_distributed,
# which is not installed.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/core/bounce/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/bounce COMPONENT development
        FILES_MATCHING PATTERN "*.h" PATTERN "distributed_bake.h" EXCLUDE)
foreach(module ${BOUNCE_CORE_MODULES})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/core/${module}/
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/bounce/core/${module} COMPONENT development
          FILES_MATCHING PATTERN "*.h")
endforeach()

# The example scenes, to bake straight after installing:
# bounce bake <prefix>/share/bounce/scenes/cornell-box --out bakes/cornell-box
install(DIRECTORY ${PROJECT_SOURCE_DIR}/resources/scenes/
        DESTINATION ${CMAKE_INSTALL_DATADIR}/bounce/scenes COMPONENT data
        PATTERN "*.py" EXCLUDE)
# Bounce's own code states no licence yet; what is installed is the credits
# and terms of the third-party scenes.
install(FILES ${PROJECT_SOURCE_DIR}/resources/scenes/README.md
        DESTINATION ${BOUNCE_INSTALL_DOCDIR}/scenes COMPONENT licences)
foreach(scene cornell-box cornell-bunny)
  install(FILES ${PROJECT_SOURCE_DIR}/resources/scenes/${scene}/CREDITS.md
          DESTINATION ${BOUNCE_INSTALL_DOCDIR}/scenes/${scene} COMPONENT licences)
endforeach()
