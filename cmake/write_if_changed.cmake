# write_if_changed(PATH CONTENT): writes a generated file only when its
# content changes, so that nothing depending on it rebuilds needlessly.
function(write_if_changed path content)
  if(EXISTS ${path})
    file(READ ${path} old)
  endif()
  if(NOT "${old}" STREQUAL "${content}")
    file(WRITE ${path} "${content}")
  endif()
endfunction()
