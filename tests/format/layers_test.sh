#!/usr/bin/env bash
# The layer check (check_layers.py) passes on the project and fails on planted violations: a
# ground-level file that includes the loader, a public header included below its code, a public
# header implemented in two folders, and a new folder nobody placed. Each on a copy of the two
# checked roots.
# usage: layers_test.sh SOURCE_DIR WORK_DIR
set -u
source=$1 work=$2
check=$source/tests/format/check_layers.py
failures=0
python3 "$check" "$source" || { echo "FAIL: the project itself breaks its layers (above)"; failures=$((failures + 1)); }
plant() {  # plant NAME EXPECTED COMMAND...: run COMMAND in a fresh copy; the check must name EXPECTED
  local name=$1 expected=$2
  shift 2
  local copy=$work/$name
  rm -rf "$copy" && mkdir -p "$copy/tests/format" && cp -r "$source/libbodyfmt" "$source/converters" "$copy/" || exit 2
  (cd "$copy" && "$@") || exit 2
  out=$(python3 "$check" "$copy")
  if [ $? = 0 ] || ! grep -qF -- "$expected" <<<"$out"; then
    echo "FAIL: $name: the check did not name '$expected':"
    echo "$out"
    failures=$((failures + 1))
  else
    echo "ok: $name: $(grep -F -- "$expected" <<<"$out" | head -1)"
  fi
}
plant text_includes_loader "libbodyfmt/src/text/text_util.cpp: includes load/scalar.h" \
  sed -i '1i #include "load/scalar.h"' libbodyfmt/src/text/text_util.cpp
plant mesh_includes_tessellate "libbodyfmt/src/mesh/mesh.cpp: includes bodyfmt/tessellate.h" \
  sed -i '1i #include <bodyfmt/tessellate.h>' libbodyfmt/src/mesh/mesh.cpp
plant io_includes_model "libbodyfmt/src/io/read_file.cpp: includes bodyfmt/model.h" \
  sed -i '1i #include <bodyfmt/model.h>' libbodyfmt/src/io/read_file.cpp
plant core_includes_export "converters/core/loss.cpp: includes bodyfmt/converters/shape_plan.h" \
  sed -i '1i #include <bodyfmt/converters/shape_plan.h>' converters/core/loss.cpp
plant header_with_two_homes "libbodyfmt/include/bodyfmt/yaml.h: implemented in diff, yaml" \
  cp libbodyfmt/src/yaml/yaml.cpp libbodyfmt/src/diff/yaml.cpp
plant unplaced_folder "libbodyfmt/src/newthing: a folder with no layer" \
  sh -c 'mkdir libbodyfmt/src/newthing && echo "int x;" > libbodyfmt/src/newthing/a.cpp'
echo "$failures failures"
[ "$failures" = 0 ]
