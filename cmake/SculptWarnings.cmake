# Warnings as an interface target: every sculpt target links sculpt::warnings
# privately, so the flags never leak into code that includes our headers.
add_library(sculpt_warnings INTERFACE)
add_library(sculpt::warnings ALIAS sculpt_warnings)
target_compile_options(sculpt_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion>)
