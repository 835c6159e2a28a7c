# storey_warnings(<target>): warnings on for Storey's own code.
function(storey_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic
                         $<$<CXX_COMPILER_ID:GNU>:-Wshadow=local>)
  if(STOREY_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
