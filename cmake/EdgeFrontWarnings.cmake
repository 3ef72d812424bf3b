# edgefront_set_warnings(<target>): the project's warning flags, per target.
function(edgefront_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow)
  if(EDGEFRONT_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
