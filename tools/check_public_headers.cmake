# Front ends use the public surface only (docs/architecture.md).
#
#   cmake -DSOURCE_DIR=<repository> -P tools/check_public_headers.cmake
#
# Scans every header and source of the front ends (app/, views/, python/) for
# #include "MODULE/NAME.h" where MODULE is a folder of core/: those are the
# library's private headers. The public ones are included as "bounce/NAME.h"
# (core/bounce/). Each private include must be listed, as
# "FILE HEADER", in tools/private_includes_allowed.txt: the front-end
# includes not yet moved to the public headers. Fails on a private include
# missing from the list (a front end reached into the library again) and on
# a listed one that is gone (the list only shrinks, so remove its line).
cmake_minimum_required(VERSION 3.25)

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "pass -DSOURCE_DIR=<repository>")
endif()

file(GLOB module_dirs LIST_DIRECTORIES true RELATIVE ${SOURCE_DIR}/core ${SOURCE_DIR}/core/*)
set(modules)
foreach(m ${module_dirs})
  if(IS_DIRECTORY ${SOURCE_DIR}/core/${m} AND NOT m STREQUAL "bounce")
    list(APPEND modules ${m})
  endif()
endforeach()
list(JOIN modules "|" module_pattern)

file(GLOB_RECURSE front_end_files RELATIVE ${SOURCE_DIR}
     ${SOURCE_DIR}/app/*.h ${SOURCE_DIR}/app/*.cpp ${SOURCE_DIR}/views/*.h ${SOURCE_DIR}/views/*.cpp
     ${SOURCE_DIR}/python/*.h ${SOURCE_DIR}/python/*.cpp)
list(SORT front_end_files)

set(found)
foreach(f ${front_end_files})
  file(STRINGS ${SOURCE_DIR}/${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]+\"(${module_pattern})/")
  foreach(line ${lines})
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]+\"([^\"]+)\".*" "\\1" header "${line}")
    list(APPEND found "${f} ${header}")
  endforeach()
endforeach()

set(allowed)
file(STRINGS ${SOURCE_DIR}/tools/private_includes_allowed.txt list_lines)
foreach(line ${list_lines})
  string(STRIP "${line}" line)
  if(line STREQUAL "" OR line MATCHES "^#")
    continue()
  endif()
  list(APPEND allowed "${line}")
endforeach()

set(failed FALSE)
foreach(entry ${found})
  if(NOT entry IN_LIST allowed)
    message(NOTICE "private header included by a front end: ${entry} "
                   "(include the public bounce/ header that offers it instead)")
    set(failed TRUE)
  endif()
endforeach()
foreach(entry ${allowed})
  if(NOT entry IN_LIST found)
    message(NOTICE "tools/private_includes_allowed.txt lists '${entry}', "
                   "which is no longer included: remove the line")
    set(failed TRUE)
  endif()
endforeach()
list(LENGTH found count)
list(LENGTH allowed allowed_count)
if(failed)
  message(FATAL_ERROR "front ends: ${count} private includes, ${allowed_count} allowed")
endif()
message(STATUS "front ends: ${count} private includes, all on the allow-list")
