# integration.Install.FindPackage: an outside project (outside_project/)
# configured and built against the installed prefix alone, with
# find_package(Bounce). The installed `bounce` bakes the installed Cornell
# box and `bounce solve` lights it with a moved light; then
#   relight (Bounce::core)   opens the bake and scene, moves the same light,
#                            lights a frame: E, b and T b per patch must be
#                            the bytes solve wrote;
#   engine (Bounce::runtime) multiplies the bake's matrix by solve's b, the
#                            direct light an engine computes itself: T b must
#                            be solve's; and it needs none of Assimp, Qt, VTK
#                            or MPI (its dynamic section).
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/run_checked.cmake)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(bounce ${PREFIX}/bin/bounce)
# The light moved, by name, for both.
set(light ceiling-point 0.1 1.5 0.3)
set(light_spec ceiling-point:0.1,1.5,0.3)

# A small bake: the test is about the relight, not the bake's quality.
run_checked(ignored WORKING_DIRECTORY ${WORK}
            COMMAND ${bounce} bake ${PREFIX}/share/bounce/scenes/cornell-box --out bake --voxel 8
                    --final-gather-rays 64 --quiet)
run_checked(ignored WORKING_DIRECTORY ${WORK}
            COMMAND ${bounce} solve bake --float32 --light ${light_spec} --out solve --quiet
                    --no-images --no-mesh)

run_checked(ignored COMMAND ${CMAKE_COMMAND} -S ${CMAKE_CURRENT_LIST_DIR}/outside_project
                            -B ${WORK}/outside -G Ninja -DCMAKE_BUILD_TYPE=Release
                            -DCMAKE_PREFIX_PATH=${PREFIX})
run_checked(ignored COMMAND ${CMAKE_COMMAND} --build ${WORK}/outside)

run_checked(said WORKING_DIRECTORY ${WORK}
            COMMAND ${WORK}/outside/relight bake ${light} relit.npy)
message(STATUS "relight: ${said}")
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/solve/patch_light.npy
                        ${WORK}/relit.npy RESULT_VARIABLE differ)
if(differ)
  message(FATAL_ERROR "the outside project's E, b, T b differ from bounce solve's "
                      "(${WORK}/relit.npy, ${WORK}/solve/patch_light.npy)")
endif()

run_checked(said WORKING_DIRECTORY ${WORK}
            COMMAND ${WORK}/outside/engine bake solve/patch_light.npy)
message(STATUS "engine: ${said}")
run_checked(dynamic COMMAND readelf -d ${WORK}/outside/engine)
string(TOLOWER "${dynamic}" dynamic)
foreach(unwanted assimp qt5 vtk mpi)
  if(dynamic MATCHES "needed[^\n]*${unwanted}")
    message(FATAL_ERROR "the engine, linked with Bounce::runtime, needs ${unwanted}:\n${dynamic}")
  endif()
endforeach()
