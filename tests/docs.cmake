# ctest `docs`: what the READMEs name exists, and what they count is the
# count.  Run with -DSRC=<source dir>.
#   - every path in backquotes in README.md and in the README.md of every
#     room (dem/, continuum/, app/*, verify/*, cli/, tests/, bench/, cases/)
#     exists: from the repository root, from the README's folder or from
#     the folder above it ("decks/deck.h" in app/kinds/README.md); a path
#     with a placeholder (<kind>, *, {h,cpp}) is a pattern and is skipped;
#   - README.md's range of checks (V01-VNN) ends at the registry's last id.
set(_bad "")
file(GLOB _readmes "${SRC}/README.md" "${SRC}/*/README.md" "${SRC}/app/*/README.md" "${SRC}/verify/*/README.md"
     "${SRC}/tests/*/README.md")
set(_paths 0)
foreach(_readme ${_readmes})
  file(READ "${_readme}" _text)
  get_filename_component(_here "${_readme}" DIRECTORY)
  get_filename_component(_above "${_here}" DIRECTORY)
  string(REGEX MATCHALL "`(dem|continuum|app|verify|cli|cases|tests|bench|docs|cmake|decks|io|run|kinds|plot|studies|reference|checks|report)/[^` ]*`" _named "${_text}")
  foreach(_p ${_named})
    string(REPLACE "`" "" _p "${_p}")
    if(_p MATCHES "[<>*{}]")
      continue()
    endif()
    math(EXPR _paths "${_paths} + 1")
    if(NOT EXISTS "${SRC}/${_p}" AND NOT EXISTS "${_here}/${_p}" AND NOT EXISTS "${_above}/${_p}")
      file(RELATIVE_PATH _rel "${SRC}" "${_readme}")
      list(APPEND _bad "${_rel} names ${_p}, which does not exist")
    endif()
  endforeach()
endforeach()

file(READ "${SRC}/verify/checks/checks_registry.cpp" _registry)
string(REGEX MATCHALL "\"V[0-9][0-9]\"" _ids "${_registry}")
list(REMOVE_DUPLICATES _ids)
list(SORT _ids)
list(GET _ids -1 _last)
string(REPLACE "\"" "" _last "${_last}")
file(READ "${SRC}/README.md" _readme_text)
string(REGEX MATCH "V01-V[0-9][0-9]" _range "${_readme_text}")
if(NOT _range STREQUAL "V01-${_last}")
  list(APPEND _bad "README.md gives the checks as '${_range}': the registry's last check is ${_last}")
endif()

if(_bad)
  string(REPLACE ";" "\n" _msg "${_bad}")
  message(FATAL_ERROR "docs stale:\n${_msg}")
endif()
list(LENGTH _readmes _n)
message(STATUS "docs hold: ${_paths} paths in ${_n} READMEs exist; checks V01-${_last}")
