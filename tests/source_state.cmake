# cmake/source_state.cmake on a scratch tree WORK: the sources' hash is the
# same when nothing changed, changes with any source of dem/, continuum/ or
# app/ (its contents or its name, each kind of file), ignores files that
# make no result (docs) and editors' hidden files (a dangling lock link
# included); the header is not rewritten when its content stays, so nothing
# rebuilds; git_sha.h is written even outside a git work tree.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/src/dem ${WORK}/src/continuum ${WORK}/src/app/io ${WORK}/src/docs ${WORK}/out)
file(WRITE ${WORK}/src/dem/law.h "double k = 1;\n")
file(WRITE ${WORK}/src/dem/law.cpp "int a;\n")
file(WRITE ${WORK}/src/continuum/ode.cpp "int b;\n")
file(WRITE ${WORK}/src/app/io/out.h "int c;\n")
file(WRITE ${WORK}/src/app/io/out.cpp "int d;\n")
file(WRITE ${WORK}/src/app/io/info.h.in "@X@\n")
file(WRITE ${WORK}/src/docs/notes.md "notes\n")

function(hash_now result)
  # The scratch tree may lie inside a git work tree (a build folder): git
  # must not look above it.
  execute_process(COMMAND ${CMAKE_COMMAND} -E env GIT_CEILING_DIRECTORIES=${WORK}
                          ${CMAKE_COMMAND} -DSRC=${WORK}/src -DOUT=${WORK}/out -P ${SCRIPT}
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "source_state.cmake failed: ${rc}")
  endif()
  file(READ ${WORK}/out/sources_sha256.h text)
  string(REGEX MATCH "\"([0-9a-f]+)\"" _ "${text}")
  string(LENGTH "${CMAKE_MATCH_1}" n)
  if(NOT n EQUAL 64)
    message(FATAL_ERROR "no SHA-256 in sources_sha256.h: ${text}")
  endif()
  set(${result} ${CMAKE_MATCH_1} PARENT_SCOPE)
endfunction()

function(expect what a b same)
  if(same AND NOT a STREQUAL b)
    message(FATAL_ERROR "${what}: the hash changed (${a} -> ${b})")
  elseif(NOT same AND a STREQUAL b)
    message(FATAL_ERROR "${what}: the hash did not change")
  endif()
endfunction()

hash_now(last)
file(READ ${WORK}/out/git_sha.h git_sha)
if(NOT git_sha MATCHES "git_sha = \"unknown\"")
  message(FATAL_ERROR "outside a git work tree git_sha.h says: ${git_sha}")
endif()
file(TIMESTAMP ${WORK}/out/sources_sha256.h written "%s")
execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 1.1)
hash_now(again)
expect("nothing changed" ${last} ${again} TRUE)
file(TIMESTAMP ${WORK}/out/sources_sha256.h rewritten "%s")
if(NOT written STREQUAL rewritten)
  message(FATAL_ERROR "sources_sha256.h was rewritten with the same content")
endif()

file(WRITE ${WORK}/src/docs/notes.md "other notes\n")
file(WRITE "${WORK}/src/dem/.#law.cpp" "an editor's lock\n")
file(CREATE_LINK ${WORK}/src/nowhere "${WORK}/src/app/io/.#out.cpp" SYMBOLIC)
hash_now(ignored)
expect("a docs file edited, editors' files added" ${last} ${ignored} TRUE)

foreach(f dem/law.h dem/law.cpp continuum/ode.cpp app/io/out.h app/io/out.cpp app/io/info.h.in)
  file(APPEND ${WORK}/src/${f} "// edited\n")
  hash_now(edited)
  expect("${f} edited" ${last} ${edited} FALSE)
  set(last ${edited})
endforeach()

file(RENAME ${WORK}/src/dem/law.h ${WORK}/src/dem/law2.h)
hash_now(renamed)
expect("an engine header renamed" ${last} ${renamed} FALSE)
