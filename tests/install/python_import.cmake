# integration.Install.PythonImport: `import bounce` with only the prefix's
# site-packages added to Python's path, from a folder that is neither tree,
# finds the installed module.
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/run_checked.cmake)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(site ${PREFIX}/${PYTHON_DIR})
run_checked(module WORKING_DIRECTORY ${WORK}
            COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${site} ${PYTHON} -c
                    "import bounce; print(bounce.__file__)")
string(STRIP "${module}" module)
get_filename_component(module_dir ${module} DIRECTORY)
if(NOT module_dir STREQUAL site)
  message(FATAL_ERROR "imported ${module}, not the module in ${site}")
endif()
