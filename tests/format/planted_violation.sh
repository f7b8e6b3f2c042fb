#!/usr/bin/env bash
# check_format.sh must find a misformatted file in a folder nobody listed, both in a git
# checkout and in a plain copy of the tree, and must leave out tests/data and build trees.
# Usage: planted_violation.sh CLANG_FORMAT SOURCE_DIR WORK_DIR
set -euo pipefail
clang_format=$1 source_dir=$2 work=$3
check=$source_dir/tests/format/check_format.sh
fail() { echo "FAIL: $*" >&2; exit 1; }

plant() {
  rm -rf "$1" && mkdir -p "$1/brand_new_folder" "$1/tests/data" "$1/build-x" "$1/src"
  cp "$source_dir/.clang-format" "$1/"
  printf 'int ok() { return 0; }\n' >"$1/src/ok.cpp"
  printf 'int   bad( ){return 1;}\n' >"$1/brand_new_folder/bad.cpp"
  printf 'int   data( ){return 1;}\n' >"$1/tests/data/input.cpp"
  printf 'int   generated( ){return 1;}\n' >"$1/build-x/generated.cpp"
  printf '/build*/\n' >"$1/.gitignore"
}

expect() {  # TREE: reports brand_new_folder/bad.cpp alone, then passes once it is formatted
  local out rc=0
  out=$(bash "$check" "$clang_format" "$1" 2>&1) || rc=$?
  [ "$rc" -eq 1 ] || fail "$1: exit $rc, expected 1: $out"
  grep -q 'not formatted: brand_new_folder/bad.cpp' <<<"$out" || fail "$1: the planted file is not named: $out"
  ! grep -q -e 'tests/data' -e 'build-x' -e 'ok.cpp' <<<"$out" || fail "$1: reported a file it must not: $out"
  "$clang_format" -i "$1/brand_new_folder/bad.cpp"
  bash "$check" "$clang_format" "$1" >/dev/null || fail "$1: still fails once the planted file is formatted"
}

plant "$work/plain"
expect "$work/plain"
plant "$work/checkout"
git -C "$work/checkout" init -q
git -C "$work/checkout" add .
expect "$work/checkout"
echo "planted violations found in a plain tree and in a git checkout"
