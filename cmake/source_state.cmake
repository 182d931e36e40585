# Writes, in the folder OUT, what the sources of this build are:
#   git_sha.h         the current git SHA (suffix -dirty if tracked files are
#                     modified), for provenance;
#   sources_sha256.h  the SHA-256 of demvv's own sources (dem/, continuum/,
#                     app/, verify/, cli/: every .h, .cpp and .in file by its path and
#                     contents; editors' hidden files left out), git or
#                     not: it keys the sample cache, so a sample prepared
#                     by another build is never served.
# Run at every build, so neither is ever stale; a file is only rewritten when
# its content changes, so nothing rebuilds needlessly.
include(${CMAKE_CURRENT_LIST_DIR}/write_if_changed.cmake)

execute_process(COMMAND git rev-parse --short=12 HEAD
  WORKING_DIRECTORY ${SRC} OUTPUT_VARIABLE sha OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
execute_process(COMMAND git status --porcelain --untracked-files=no
  WORKING_DIRECTORY ${SRC} OUTPUT_VARIABLE dirty OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT sha)
  set(sha "unknown")
elseif(dirty)
  set(sha "${sha}-dirty")
endif()
write_if_changed(${OUT}/git_sha.h
  "#pragma once\nnamespace build_info { inline constexpr const char *git_sha = \"${sha}\"; }\n")

set(patterns "")
foreach(dir dem continuum app verify cli)
  list(APPEND patterns ${SRC}/${dir}/*.h ${SRC}/${dir}/*.cpp ${SRC}/${dir}/*.in)
endforeach()
file(GLOB_RECURSE sources RELATIVE ${SRC} ${patterns})
list(SORT sources)
set(listing "")
foreach(f IN LISTS sources)
  get_filename_component(name ${f} NAME)
  if(name MATCHES "^[.#]" OR NOT EXISTS ${SRC}/${f}) # an editor's lock or backup file
    continue()
  endif()
  file(SHA256 ${SRC}/${f} h)
  string(APPEND listing "${h}  ${f}\n")
endforeach()
string(SHA256 hash "${listing}")
write_if_changed(${OUT}/sources_sha256.h
  "#pragma once\nnamespace build_info { inline constexpr const char *sources_sha256 = \"${hash}\"; }\n")
