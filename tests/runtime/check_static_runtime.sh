#!/bin/bash
# Checks what tools/CMakeLists.txt (bodyfmt_static_runtime) promises of a tool linked with the
# static C++ runtime: it needs neither libstdc++.so nor libfmt.so, and its dynamic symbol table
# exports no C++ symbol. A dlopen()ed module that brings the shared runtime (the assimp mesh
# module) then binds all of it there, instead of half of it to the tool's copy. Then both tools
# import meshes through that module: a refused STL (the module reports it through the tool's
# callback) and an OBJ (its box must arrive intact).
# Usage: check_static_runtime.sh BODYCHECK BODYINFO
set -u
here=$(cd "$(dirname "$0")" && pwd)
bodycheck=$1
bodyinfo=$2
status=0
for tool in "$bodycheck" "$bodyinfo"; do
  needed=$(readelf -d "$tool" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
  if [ -z "$needed" ]; then
    echo "FAIL: $tool: readelf found no NEEDED entries (not a dynamic executable?)"
    status=1
  fi
  for lib in $needed; do
    case "$lib" in
      libstdc++.so*|libfmt.so*) echo "FAIL: $tool needs $lib"; status=1 ;;
    esac
  done
  exported=$(nm -D --defined-only "$tool" | awk '{print $NF}' | grep '^_Z' | head -5)
  if [ -n "$exported" ]; then
    echo "FAIL: $tool exports C++ symbols, which a module would bind to:"
    echo "$exported"
    status=1
  fi
  [ $status -eq 0 ] && echo "ok: $tool needs only: $(echo $needed | tr '\n' ' ')"
done

out=$("$bodycheck" --color never "$here/broken_mesh.body" 2>&1)
code=$?
if [ $code -ne 1 ] || ! grep -q 'broken_mesh.body:13:42: error: cannot read mesh file .*\[mesh-parse\]' <<<"$out"; then
  echo "FAIL: bodycheck on broken_mesh.body (exit $code; expected 1 and a located mesh-parse error):"
  echo "$out"
  status=1
fi
out=$("$bodyinfo" --format yaml "$here/broken_mesh.body" 2>/dev/null)
if ! grep -qx '  visual_bbox: \[0, 0, 0, 2, 1, 0\]' <<<"$out"; then
  echo "FAIL: bodyinfo did not read square.obj's box [0, 0, 0, 2, 1, 0] through the module:"
  echo "$out"
  status=1
fi
[ $status -eq 0 ] && echo "ok: both tools read meshes through the assimp module"
exit $status
