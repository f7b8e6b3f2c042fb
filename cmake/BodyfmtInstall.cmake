# Installation: the shared library, its public headers, the command-line tools, and a
# CMake package so that other projects can do
#   find_package(bodyfmt REQUIRED)
#   target_link_libraries(app PRIVATE bodyfmt::bodyfmt)
# libyaml and fmt are PRIVATE dependencies of the shared library, and assimp is only linked by
# the importer module it loads at run time, so the package only needs Eigen (the public
# headers use it).
include(CMakePackageConfigHelpers)

set(BODYFMT_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/bodyfmt" CACHE STRING
    "Where bodyfmtConfig.cmake is installed, relative to the prefix")

install(TARGETS bodyfmt EXPORT bodyfmtTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The assimp importer module: libbodyfmt dlopen()s it from its own directory, so it goes into
# the same lib dir. Not exported: it is a plug-in of libbodyfmt, not something to link against.
install(TARGETS bodyfmt_assimp LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/libbodyfmt/include/bodyfmt
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.h")

# Tools: every executable defined in these folders (so new tools are installed without
# touching this file). The tools link libbodyfmt statically (bodyfmt::static), so they need no
# RPATH; they find the assimp module in the library folder (src/mesh_import/assimp_module.cpp).
set(BODYFMT_TOOL_DIRS tools)
# Developer utilities that build the docs; not installed.
set(BODYFMT_INTERNAL_TOOLS rules_doc keys_doc)
get_property(_bodyfmt_subdirs DIRECTORY ${PROJECT_SOURCE_DIR} PROPERTY SUBDIRECTORIES)
foreach(_dir IN LISTS BODYFMT_TOOL_DIRS)
  if(NOT "${PROJECT_SOURCE_DIR}/${_dir}" IN_LIST _bodyfmt_subdirs)
    continue()
  endif()
  get_property(_targets DIRECTORY ${PROJECT_SOURCE_DIR}/${_dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(_target IN LISTS _targets)
    get_target_property(_type ${_target} TYPE)
    if(_type STREQUAL "EXECUTABLE" AND NOT _target IN_LIST BODYFMT_INTERNAL_TOOLS)
      install(TARGETS ${_target} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    endif()
  endforeach()
endforeach()

install(EXPORT bodyfmtTargets
  NAMESPACE bodyfmt::
  FILE bodyfmtTargets.cmake
  DESTINATION ${BODYFMT_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/bodyfmtConfig.cmake.in
  ${PROJECT_BINARY_DIR}/bodyfmtConfig.cmake
  INSTALL_DESTINATION ${BODYFMT_INSTALL_CMAKEDIR})
# 0.x: a minor version bump may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/bodyfmtConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES
  ${PROJECT_BINARY_DIR}/bodyfmtConfig.cmake
  ${PROJECT_BINARY_DIR}/bodyfmtConfigVersion.cmake
  DESTINATION ${BODYFMT_INSTALL_CMAKEDIR})
# The manual next to the licence, in the folders the tools' --help names them by (docs/rules.md,
# dynamics/README.md), so that a path in --help is a path under share/doc/bodyfmt.
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/bodyfmt)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/bodyfmt/docs)
install(FILES ${PROJECT_SOURCE_DIR}/dynamics/README.md DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/bodyfmt/dynamics)
# The editor set-ups that start bodyls (bodyls --help names this folder).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/editors/ DESTINATION ${CMAKE_INSTALL_DATADIR}/bodyfmt/editors)
