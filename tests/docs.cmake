# ctest `docs`: what the READMEs name exists, and what they count is the
# count.  Run with -DSRC=<source dir>.
#   - every path in backquotes in README.md and in the README.md of every
#     room (dem/, continuum/, app/*, verify/*, cli/, tests/, bench/, cases/)
#     exists: from the repository root, from the README's folder or from
#     the folder above it ("decks/deck.h" in app/kinds/README.md); a path
#     with a placeholder (<kind>, *, {h,cpp}) is a pattern and is skipped;
#   - README.md's range of checks (V01-VNN) ends at the registry's last id;
#   - README.md's recipe for a deck kind names the tables of kinds and the
#     figures' file, and every row of the tables names its kind's declare
#     and figures functions (declared in app/plot/run_figures.h).
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

# README's recipe for a deck kind names its files and one row: every row of
# the tables of kinds names the kind's declare, parse, run and figures, the
# figures are declared in the file the recipe names, and the recipe names
# the two tables and the figures' file.
string(FIND "${_readme_text}" "**A deck kind.**" _at)
string(SUBSTRING "${_readme_text}" ${_at} -1 _recipe)
string(FIND "${_recipe}" "\n\n" _end)
string(SUBSTRING "${_recipe}" 0 ${_end} _recipe)
foreach(_named app/kinds/deck_kinds.cpp app/kinds/dem_kinds.cpp app/plot/run_figures.cpp app/run/dem_driver.h)
  string(FIND "${_recipe}" "`${_named}`" _found)
  if(_found LESS 0)
    list(APPEND _bad "README.md's recipe for a deck kind does not name ${_named}")
  endif()
endforeach()
file(READ "${SRC}/app/plot/run_figures.h" _figures_header)
set(_kinds 0)
foreach(_table app/kinds/dem_kinds.cpp app/kinds/deck_kinds.cpp)
  file(READ "${SRC}/${_table}" _rows_text)
  string(REGEX MATCHALL "{\"[a-z_]+\",[ \n]*\"" _rows "${_rows_text}")
  string(REGEX MATCHALL "&declare_[a-z_]+" _declares "${_rows_text}")
  string(REGEX MATCHALL "&[a-z_]+_run_figures" _figures "${_rows_text}")
  list(LENGTH _rows _n_rows)
  list(LENGTH _declares _n_declares)
  list(LENGTH _figures _n_figures)
  math(EXPR _kinds "${_kinds} + ${_n_rows}")
  if(NOT _n_rows EQUAL _n_declares OR NOT _n_rows EQUAL _n_figures)
    list(APPEND _bad "${_table}: ${_n_rows} rows, ${_n_declares} declare and ${_n_figures} figures functions: each row names its own")
  endif()
  foreach(_f ${_figures})
    string(REPLACE "&" "" _f "${_f}")
    string(FIND "${_figures_header}" "void ${_f}(" _declared)
    if(_declared LESS 0)
      list(APPEND _bad "${_table} names ${_f}, which app/plot/run_figures.h does not declare")
    endif()
  endforeach()
endforeach()

if(_bad)
  string(REPLACE ";" "\n" _msg "${_bad}")
  message(FATAL_ERROR "docs stale:\n${_msg}")
endif()
list(LENGTH _readmes _n)
message(STATUS "docs hold: ${_paths} paths in ${_n} READMEs exist; checks V01-${_last}; ${_kinds} kinds, each a whole row")
