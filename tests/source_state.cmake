# cmake/source_state.cmake on a scratch tree WORK: the sources' hash is the
# same when nothing changed, changes with any engine or harness source (its
# contents or its name), and ignores files that make no result (docs, cases).
# The header is not rewritten when its content stays, so nothing rebuilds.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/src/dem ${WORK}/src/verify/io ${WORK}/src/docs ${WORK}/out)
file(WRITE ${WORK}/src/dem/law.h "double k = 1;\n")
file(WRITE ${WORK}/src/verify/io/info.h.in "@X@\n")
file(WRITE ${WORK}/src/docs/notes.md "notes\n")

function(hash_now result)
  execute_process(COMMAND ${CMAKE_COMMAND} -DSRC=${WORK}/src -DOUT=${WORK}/out -P ${SCRIPT}
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

hash_now(first)
file(TIMESTAMP ${WORK}/out/sources_sha256.h written "%s")
execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 1.1)
hash_now(again)
expect("nothing changed" ${first} ${again} TRUE)
file(TIMESTAMP ${WORK}/out/sources_sha256.h rewritten "%s")
if(NOT written STREQUAL rewritten)
  message(FATAL_ERROR "sources_sha256.h was rewritten with the same content")
endif()

file(WRITE ${WORK}/src/docs/notes.md "other notes\n")
hash_now(docs)
expect("a docs file edited" ${first} ${docs} TRUE)

file(WRITE ${WORK}/src/dem/law.h "double k = 2;\n")
hash_now(edited)
expect("an engine header edited" ${first} ${edited} FALSE)

file(RENAME ${WORK}/src/dem/law.h ${WORK}/src/dem/law2.h)
hash_now(renamed)
expect("an engine header renamed" ${edited} ${renamed} FALSE)

file(WRITE ${WORK}/src/verify/io/info.h.in "@Y@\n")
hash_now(template)
expect("a harness template edited" ${renamed} ${template} FALSE)
