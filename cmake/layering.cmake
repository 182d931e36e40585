# ctest `layering`: the floors of the tree, held on every #include "..." of
# every source.  Run with -DSRC=<source dir>.
#
# The rooms from the floor up, and what each may include besides itself
# (a folder ending in '/' stands for all its headers, a file for itself):
#   dem/            the DEM engine (Eigen, GSL, OpenMP)
#   continuum/      the continuum companion (deal.II, SUNDIALS)
#   app/io/         files
#   app/decks/      the deck reader, handed its kinds
#   app/reference/  closed forms and convergence tables
#   app/run/        what every run shares
#   app/plot/       figures
#   app/kinds/      the deck kinds and their table
#   app/studies/    ensembles of runs
#   verify/checks/  the checks, their registry and catalogue
#   verify/report/  the report
#   cli/            the demvv executable
#   bench/, tests/  anything
# Each room's README.md (dem/ and continuum/ included) ends its job with a
# paragraph "May include: ..." that names, in backquotes, exactly these
# entries (what follows "never" is what it may not): the test fails when a README and this table differ,
# so the READMEs cannot go stale.
cmake_policy(SET CMP0007 NEW)
set(_rooms
  "dem|"
  "continuum|"
  "app/io|dem/"
  "app/decks|dem/ app/io/"
  "app/reference|dem/ continuum/burgers_chain.h continuum/burgers_ode.h"
  "app/run|dem/ continuum/numerical_failure.h app/decks/ app/io/"
  "app/plot|app/decks/ app/io/"
  "app/kinds|dem/ continuum/ app/decks/ app/io/ app/reference/ app/run/ app/plot/"
  "app/studies|continuum/cylinder.h app/decks/ app/io/ app/run/ app/plot/ app/kinds/"
  "verify/checks|dem/ continuum/ app/decks/ app/io/ app/reference/ app/run/ app/plot/ app/kinds/ app/studies/"
  "verify/report|app/io/ app/plot/ verify/checks/"
  "cli|dem/ continuum/cylinder.h app/decks/ app/io/ app/run/ app/plot/ app/kinds/ app/studies/ verify/checks/ verify/report/")

set(_bad "")
set(_checked 0)
foreach(_row ${_rooms})
  string(REPLACE "|" ";" _row "${_row}")
  list(GET _row 0 _room)
  list(LENGTH _row _n)
  set(_allowed "${_room}/")
  if(_n GREATER 1)
    list(GET _row 1 _more)
    string(REPLACE " " ";" _more "${_more}")
    list(APPEND _allowed ${_more})
  endif()
  # The includes of every source of the room.
  file(GLOB_RECURSE _files "${SRC}/${_room}/*.h" "${SRC}/${_room}/*.cpp" "${SRC}/${_room}/*.in")
  if(NOT _files)
    list(APPEND _bad "${_room}/: no sources (a room of the table is missing)")
  endif()
  foreach(_f ${_files})
    file(STRINGS "${_f}" _lines REGEX "^#include \"[a-z_]+/")
    foreach(_line ${_lines})
      string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" _header "${_line}")
      # tests/ and bench/ headers are their own rooms' (fuzz support).
      if(NOT _header MATCHES "^(dem|continuum|app|verify|cli)/")
        continue()
      endif()
      math(EXPR _checked "${_checked} + 1")
      set(_ok FALSE)
      foreach(_a ${_allowed})
        string(LENGTH "${_a}" _len)
        string(SUBSTRING "${_header}" 0 ${_len} _prefix)
        if(_a MATCHES "/$" AND _prefix STREQUAL _a)
          set(_ok TRUE)
        elseif(_header STREQUAL _a)
          set(_ok TRUE)
        endif()
      endforeach()
      if(NOT _ok)
        file(RELATIVE_PATH _rel "${SRC}" "${_f}")
        string(REPLACE ";" " " _may "${_allowed}")
        list(APPEND _bad "${_rel} includes ${_header}: ${_room}/ may include ${_may}")
      endif()
    endforeach()
  endforeach()
  # The room's README says the same.
  set(_readme "${SRC}/${_room}/README.md")
  if(NOT EXISTS "${_readme}")
    list(APPEND _bad "${_room}/README.md is missing")
    continue()
  endif()
  file(READ "${_readme}" _text)
  string(FIND "${_text}" "May include:" _at)
  if(_at LESS 0)
    list(APPEND _bad "${_room}/README.md has no \"May include:\" line")
    continue()
  endif()
  string(SUBSTRING "${_text}" ${_at} -1 _said)
  foreach(_stop "\n\n" "never")
    string(FIND "${_said}" "${_stop}" _end)
    if(_end GREATER 0)
      string(SUBSTRING "${_said}" 0 ${_end} _said)
    endif()
  endforeach()
  string(REGEX MATCHALL "`(dem|continuum|app|verify|cli)/[a-z_./]*`" _named "${_said}")
  string(REPLACE "`" "" _named "${_named}")
  list(REMOVE_DUPLICATES _named)
  list(REMOVE_ITEM _named "${_room}/")
  set(_expected ${_allowed})
  list(REMOVE_ITEM _expected "${_room}/")
  list(SORT _named)
  list(SORT _expected)
  if(NOT "${_named}" STREQUAL "${_expected}")
    string(REPLACE ";" " " _named "${_named}")
    string(REPLACE ";" " " _expected "${_expected}")
    list(APPEND _bad "${_room}/README.md's \"May include\" names [${_named}]: the layering table says [${_expected}]")
  endif()
endforeach()
if(_bad)
  string(REPLACE ";" "\n" _msg "${_bad}")
  message(FATAL_ERROR "layering broken:\n${_msg}")
endif()
list(LENGTH _rooms _count)
message(STATUS "layering holds: ${_count} rooms, ${_checked} includes, every README's \"May include\" as the table")
