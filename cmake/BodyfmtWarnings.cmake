# Warnings for the project's own targets; dependencies' headers are system includes.
add_library(bodyfmt_warnings INTERFACE)
target_compile_options(bodyfmt_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic>)
