# olcb_strict_warnings(TARGET): the implicit conversions, sign changes and shadowed names that
# -Wall -Wextra let through, as errors, on a target whose sources are clean of them (issue 29).
# PRIVATE: a library's own sources only; its headers are held to the same flags by every
# strict target that includes them. GCC and Clang spell these flags alike.
function(olcb_strict_warnings target)
    if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
        target_compile_options(${target} PRIVATE -Wconversion -Wsign-conversion -Wshadow -Werror)
    endif()
endfunction()
