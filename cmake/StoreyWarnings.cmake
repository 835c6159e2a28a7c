# storey_warnings(<target>): warnings on for Storey's own code.
function(storey_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic
                         $<$<CXX_COMPILER_ID:GNU>:-Wshadow=local>)
  if(STOREY_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# storey_no_regex_false_positive(<source>...): GCC 12 reports -Wmaybe-uninitialized
# inside <regex> (std::function moves in regex_automaton.h) when ASan instruments
# it, a false positive in the library; switched off for the files using <regex>
# in sanitizer builds only (the asan preset).
function(storey_no_regex_false_positive)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_FLAGS MATCHES "sanitize=address")
    set_source_files_properties(${ARGN}
                                PROPERTIES COMPILE_OPTIONS -Wno-maybe-uninitialized)
  endif()
endfunction()
