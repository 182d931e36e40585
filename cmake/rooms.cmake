# demvv_unity_build(TARGET): the target's sources compiled in batches of
# eight, each batch one translation unit, so that the headers every source
# of a room includes (nlohmann/json, the decks, deal.II's flags) are read
# and their templates instantiated once a batch, not once a file: the rooms
# compile in about half the time.  Names private to a source (its anonymous
# namespace) must therefore differ across the sources of one room.  The
# engine (dem/) and the continuum companion are compiled file by file: their
# code generation stays what the benchmarks measured.
function(demvv_unity_build name)
  set_target_properties(${name} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
endfunction()

# demvv_room(NAME SOURCES... LINKS targets...): one room of the application
# (app/, verify/) as a static library.  Every room is compiled alike: with
# deal.II's cached flags (deal_ii_setup_target: its include paths, its MPI;
# without its -g in a Release build), demvv's warnings, and the include
# root at the repository (and the build folder of app/, where build_info.h
# and the sources' hash are written).
# A room links the rooms below it, so its library is placed before theirs
# on every link line: a symbol a lower room took from a higher one would
# not resolve.  The layering test (cmake/layering.cmake) holds the includes
# to the same floors.
function(demvv_room name)
  cmake_parse_arguments(ROOM "" "" "SOURCES;LINKS" ${ARGN})
  add_library(${name} STATIC ${ROOM_SOURCES})
  demvv_unity_build(${name})
  add_dependencies(${name} demvv_source_state)
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR}/app)
  demvv_deal_ii_target(${name})
  # deal_ii_setup_target uses the plain signature: so must every later call.
  target_compile_options(${name} PRIVATE ${DEMVV_WARNINGS})
  if(DEMVV_FUZZ)
    # deal.II's flags are GCC's, which clang ignores where it does not know
    # them; its -O2 -g give way to the fuzz flags, which compile a third faster.
    target_compile_options(${name} PUBLIC -Wno-unknown-warning-option -Wno-ignored-optimization-argument
                           ${DEMVV_OPT_FLAGS} -fno-unroll-loops)
  endif()
  target_link_libraries(${name} ${ROOM_LINKS})
endfunction()
