# Our own code builds with warnings as errors; vendored code (Unity) does not
# call this function and so gets none of these flags.
function(ht_strict target)
  if(CMAKE_C_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE
      -Wall -Wextra -Wpedantic -Wconversion -Wshadow -Werror)
  endif()
endfunction()
