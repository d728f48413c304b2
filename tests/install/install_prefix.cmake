# integration.Install.Prefix: `cmake --install` of the whole build into a
# fresh PREFIX puts every part where docs/install.md says, and nothing
# installed points back into the source or build tree (the CMake package's
# files, the programs' run paths).
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/run_checked.cmake)
file(REMOVE_RECURSE ${PREFIX})
run_checked(ignored COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX})

set(expected bin/bounce include/bounce/relight.h include/bounce/bake_folder.h
             include/bounce/core/runtime/relighter.h include/bounce/core/base/error.h
             lib/libbounce_runtime.a lib/libbounce_core.a lib/cmake/Bounce/BounceConfig.cmake
             lib/cmake/Bounce/BounceConfigVersion.cmake lib/cmake/Bounce/BounceTargets.cmake
             share/bounce/scenes/cornell-box/scene.json
             share/doc/bounce/scenes/cornell-box/CREDITS.md
             share/doc/bounce/scenes/cornell-bunny/CREDITS.md)
set(programs bin/bounce)
if(STUDIO)
  list(APPEND expected bin/bounce-studio share/applications/bounce-studio.desktop
                       share/icons/hicolor/scalable/apps/bounce-studio.svg)
  list(APPEND programs bin/bounce-studio)
endif()
foreach(file ${expected})
  if(NOT EXISTS ${PREFIX}/${file})
    message(FATAL_ERROR "not installed: ${PREFIX}/${file}")
  endif()
endforeach()
if(PYTHON_DIR)
  file(GLOB module ${PREFIX}/${PYTHON_DIR}/bounce.*.so)
  if(NOT module)
    message(FATAL_ERROR "the Python module is not in ${PREFIX}/${PYTHON_DIR}")
  endif()
  list(APPEND programs ${module})
endif()
# The package's files name neither tree (that the headers a public header
# includes are all there, integration.Install.FindPackage finds by compiling).
# Stops the test when `text`, what `what` holds, names either tree.
function(check_names_no_tree text what)
  foreach(tree ${SOURCE_DIR} ${BUILD_DIR})
    string(FIND "${text}" "${tree}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "${what} names ${tree}:\n${text}")
    endif()
  endforeach()
endfunction()
file(GLOB package_files ${PREFIX}/lib/cmake/Bounce/*.cmake)
foreach(file ${package_files} ${PREFIX}/share/applications/bounce-studio.desktop)
  if(EXISTS ${file})
    file(READ ${file} text)
    check_names_no_tree("${text}" ${file})
  endif()
endforeach()
foreach(program ${programs})
  if(IS_ABSOLUTE ${program})
    set(path ${program})
  else()
    set(path ${PREFIX}/${program})
  endif()
  run_checked(dynamic COMMAND readelf -d ${path})
  check_names_no_tree("${dynamic}" "the dynamic section (run path) of ${path}")
endforeach()
message(STATUS "installed into ${PREFIX}")
