# Use ccache when it is installed, unless the caller chose a launcher already.
find_program(BODYFMT_CCACHE ccache)
if(BODYFMT_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  set(CMAKE_CXX_COMPILER_LAUNCHER ${BODYFMT_CCACHE})
  set(CMAKE_C_COMPILER_LAUNCHER ${BODYFMT_CCACHE})
endif()
