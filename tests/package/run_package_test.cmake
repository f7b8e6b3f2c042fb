# ctest package.find_package: install the current build into a scratch prefix, then
# configure, build and run tests/package against that prefix, as an outside user would.
#
#   cmake -DBUILD_DIR=<build> -DSOURCE_DIR=<source> -DGENERATOR=<gen>
#         [-DCXX_COMPILER=<c++>] [-DLAUNCHER=<ccache>] -P run_package_test.cmake
foreach(var BUILD_DIR SOURCE_DIR GENERATOR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_package_test.cmake: -D${var}=... is required")
  endif()
endforeach()

set(work "${BUILD_DIR}/package-test")
set(prefix "${work}/prefix")
set(consumer_build "${work}/consumer")
file(REMOVE_RECURSE "${prefix}")   # keep ${consumer_build}: reconfiguring is faster

function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "package test: ${step} failed (exit ${rc}): ${ARGN}")
  endif()
endfunction()

run("install" "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}")

set(configure_args -S "${SOURCE_DIR}/tests/package" -B "${consumer_build}" -G "${GENERATOR}"
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}"
    # Only the scratch prefix (and the system, for Eigen) may provide bodyfmt.
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
if(CXX_COMPILER)
  list(APPEND configure_args "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
endif()
if(LAUNCHER)
  list(APPEND configure_args "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}")
endif()
run("configure" "${CMAKE_COMMAND}" ${configure_args})
run("build" "${CMAKE_COMMAND}" --build "${consumer_build}")

# The consumer must have found the copy in the scratch prefix, not some other install.
file(STRINGS "${consumer_build}/CMakeCache.txt" found_dir REGEX "^bodyfmt_DIR:")
string(FIND "${found_dir}" "${prefix}/" at)
if(at EQUAL -1)
  message(FATAL_ERROR "package test: bodyfmt was found outside the scratch prefix: ${found_dir}")
endif()

# Every document an installed tool's --help points at is installed, under the same relative path
# in share/doc/bodyfmt (issue 40: only LICENSE was there while --help named docs/rules.md).
set(doc_dir "${prefix}/share/doc/bodyfmt")
file(GLOB installed_tools "${prefix}/bin/*")
set(named_docs 0)
foreach(tool IN LISTS installed_tools)
  foreach(sub "" check-tank check run)
    if(sub AND NOT tool MATCHES "bodysim$")
      continue()
    endif()
    execute_process(COMMAND "${tool}" ${sub} --help OUTPUT_VARIABLE help ERROR_QUIET RESULT_VARIABLE rc)
    string(REGEX MATCHALL "[A-Za-z_-]+(/[A-Za-z_.-]+)+\\.md" docs "${help}")
    foreach(doc IN LISTS docs)
      math(EXPR named_docs "${named_docs} + 1")
      if(NOT EXISTS "${doc_dir}/${doc}")
        message(FATAL_ERROR "package test: ${tool} ${sub} --help names ${doc}, which is not installed in ${doc_dir}")
      endif()
    endforeach()
  endforeach()
endforeach()
if(named_docs LESS 3 OR NOT EXISTS "${doc_dir}/README.md" OR NOT EXISTS "${doc_dir}/docs/rules.md")
  message(FATAL_ERROR "package test: the manual is not installed in ${doc_dir} (${named_docs} documents named by --help)")
endif()

# bodyls --help names where the editor set-ups are installed, and they are there (issue 47).
execute_process(COMMAND "${prefix}/bin/bodyls" --help OUTPUT_VARIABLE help ERROR_QUIET)
if(NOT help MATCHES "share/bodyfmt/editors" OR NOT EXISTS "${prefix}/share/bodyfmt/editors/nvim/lua/bodyls.lua"
   OR NOT EXISTS "${prefix}/share/bodyfmt/editors/emacs/bodyls.el")
  message(FATAL_ERROR "package test: bodyls --help does not name share/bodyfmt/editors, or the set-ups are not "
                      "installed there:\n${help}")
endif()

run("run" "${consumer_build}/package_consumer" "${SOURCE_DIR}/examples/simpletank.body")

# The installed tools link libbodyfmt statically and look for the assimp module in the library
# folder, before the module's build folder (libbodyfmt/src/mesh_import/assimp_module.cpp). bodyinfo must
# import the OBJ of square_mesh.body (its visual box is the rectangle's corners, [0, 0, 0] ..
# [2, 1, 0]) with the installed module: the dynamic loader's log names the file it mapped.
execute_process(COMMAND "${CMAKE_COMMAND}" -E env LD_DEBUG=files
                        "${prefix}/bin/bodyinfo" --format yaml "${SOURCE_DIR}/tests/package/square_mesh.body"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR err MATCHES "mesh-importer-unavailable")
  message(FATAL_ERROR "package test: installed bodyinfo could not import an OBJ mesh (exit ${rc}):\n${out}${err}")
endif()
if(NOT out MATCHES "visual_bbox: \\[0, 0, 0, 2, 1, 0\\]")
  message(FATAL_ERROR "package test: installed bodyinfo read the wrong box for square.obj:\n${out}")
endif()
string(REGEX MATCH "file=[^ ]*libbodyfmt_assimp\\.so \\[0\\];  generating link map" module_loaded "${err}")
string(FIND "${module_loaded}" "file=${prefix}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "package test: installed bodyinfo loaded the assimp module from outside the prefix: "
                      "'${module_loaded}'")
endif()
