# Docs and comments stand alone (docs/architecture.md, "Comments stand alone").
#
#   cmake -DSOURCE_DIR=<repository> -P tools/check_citations.cmake
#
# Fails when a doc or a source file cites a work session or an issue by
# number ("session 8", "Session 8:", "issue 4", "issues 4 and 5", "#43"):
# such a citation points at a history the reader does not have, so the text
# is to say the reason or name the benchmark section instead. In the code,
# kernels, shaders, tests and CMake files it also fails on citations of
# documents outside the repository (the patterns of the grep that
# docs/architecture.md records). Each file is read whole with every line
# break and the comment marker after it ("//", "#", "*", "--") folded into
# one space, so a citation split over two lines ("issue" at the end of one,
# "4" at the start of the next) is found like one on a single line.
# Words such as "MpiSession", "session-scoped" or "a lighting session" pass:
# only a number after the word fails.
cmake_minimum_required(VERSION 3.25)

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "pass -DSOURCE_DIR=<repository>")
endif()

set(code_dirs core app views python bench tests tools cmake kernels shaders)
set(code_globs)
foreach(d ${code_dirs})
  foreach(ext h hpp cpp cc c cl frag vert comp glsl py cmake sh txt)
    list(APPEND code_globs ${SOURCE_DIR}/${d}/*.${ext})
  endforeach()
endforeach()
file(GLOB_RECURSE code_files RELATIVE ${SOURCE_DIR} ${code_globs})
list(APPEND code_files CMakeLists.txt dev.sh .ci/run)
file(GLOB_RECURSE doc_files RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/docs/*.md
     ${SOURCE_DIR}/core/*.md ${SOURCE_DIR}/app/*.md ${SOURCE_DIR}/views/*.md
     ${SOURCE_DIR}/python/*.md ${SOURCE_DIR}/bench/*.md ${SOURCE_DIR}/tests/*.md
     ${SOURCE_DIR}/tools/*.md ${SOURCE_DIR}/cmake/*.md)
list(APPEND doc_files README.md)
list(REMOVE_DUPLICATES code_files)
# This file spells the patterns out.
list(REMOVE_ITEM code_files tools/check_citations.cmake)
list(SORT code_files)
list(SORT doc_files)

# A session or an issue by number, in any file. The character before the word
# must not be a letter, so "MpiSession 2" is not "Session 2".
set(number_citation
    "(^|[^A-Za-z])([Ss]essions?|[Ii]ssues?)[ -]#?[0-9]|(^|[ (\\[])#[0-9]+([^0-9A-Za-z_]|$)")
# Documents outside the repository, in the code only (the docs name the papers
# they follow; the code points into docs/ instead).
set(outside_citation
    "DESIGN [0-9]|[Ii]ssue [0-9]+ (§|section)|§|[Pp]aper [0-9]+ (§|section)|paper 00[0-9]")

set(hits 0)
function(check_file file pattern)
  if(NOT EXISTS ${SOURCE_DIR}/${file})
    return()
  endif()
  file(READ ${SOURCE_DIR}/${file} text)
  # One line: each line break with the comment marker that follows it becomes
  # one space, then runs of blanks one space.
  string(REGEX REPLACE "[\r\n]+[ \t]*((//+|#+|\\*+|--+)[ \t]+)?" " " text "${text}")
  string(REGEX REPLACE "[ \t]+" " " text "${text}")
  if(NOT text MATCHES "${pattern}")
    return()
  endif()
  # For the message: a few words either side, without the list separator.
  string(REPLACE ";" "," text "${text}")
  string(REGEX MATCHALL "([^ ]+ )?([^ ]+ )?[^ ]*(${pattern})[^ ]*( [^ ]+)?( [^ ]+)?" found
         "${text}")
  foreach(m IN LISTS found)
    message(NOTICE "${file}: ... ${m} ...")
    math(EXPR hits "${hits} + 1")
  endforeach()
  set(hits ${hits} PARENT_SCOPE)
endfunction()

foreach(f ${doc_files} ${code_files})
  check_file(${f} "${number_citation}")
endforeach()
foreach(f ${code_files})
  check_file(${f} "${outside_citation}")
endforeach()

list(LENGTH doc_files doc_count)
list(LENGTH code_files code_count)
if(hits GREATER 0)
  message(FATAL_ERROR "${hits} citations of a session, an issue or an outside document "
                      "(say the reason, or name the docs/ section that measures it)")
endif()
message(STATUS "no session, issue or outside-document citations in ${doc_count} docs "
               "and ${code_count} source files")
