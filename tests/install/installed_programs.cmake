# integration.Install.Programs: the installed programs run from a folder
# that is neither tree, and `bounce` reads the installed example scenes.
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/run_checked.cmake)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

run_checked(version WORKING_DIRECTORY ${WORK} COMMAND ${PREFIX}/bin/bounce --version)
if(NOT version MATCHES "^bounce ${VERSION}\n$")
  message(FATAL_ERROR "bounce --version printed '${version}', not 'bounce ${VERSION}'")
endif()
if(STUDIO)
  # --version needs no display: the studio answers it before opening one.
  run_checked(version WORKING_DIRECTORY ${WORK}
              COMMAND ${CMAKE_COMMAND} -E env --unset=DISPLAY --unset=WAYLAND_DISPLAY
                      ${PREFIX}/bin/bounce-studio --version)
  if(NOT version MATCHES "^Bounce Studio ${VERSION}\n$")
    message(FATAL_ERROR "bounce-studio --version printed '${version}'")
  endif()
endif()
run_checked(info WORKING_DIRECTORY ${WORK}
            COMMAND ${PREFIX}/bin/bounce info ${PREFIX}/share/bounce/scenes/cornell-box)
if(NOT info MATCHES "triangles")
  message(FATAL_ERROR "bounce info on the installed Cornell box printed:\n${info}")
endif()
