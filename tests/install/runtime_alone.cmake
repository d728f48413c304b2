# unit.Runtime.LinksAlone: PROGRAM, linked with the whole of bounce_runtime,
# needs none of Assimp, Qt, VTK or MPI (its dynamic section), so neither
# does an engine that links Bounce::runtime.
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/run_checked.cmake)
run_checked(dynamic COMMAND readelf -d ${PROGRAM})
string(TOLOWER "${dynamic}" dynamic)
if(NOT dynamic MATCHES "needed[^\n]*embree")
  message(FATAL_ERROR "${PROGRAM} does not link the runtime's libraries (no Embree):\n${dynamic}")
endif()
foreach(unwanted assimp qt5 vtk mpi)
  if(dynamic MATCHES "needed[^\n]*${unwanted}")
    message(FATAL_ERROR "bounce_runtime brings ${unwanted} with it:\n${dynamic}")
  endif()
endforeach()
