#!/usr/bin/env bash
# Fails when a C++ file of the project differs from what clang-format (.clang-format) makes
# of it, and lists the files. Usage: check_format.sh CLANG_FORMAT SOURCE_DIR
set -euo pipefail
clang_format=$1 source_dir=$2
cd "$source_dir"
mapfile -d '' files < <(find libbodyfmt validate converters importers tools examples bench tests \
  \( -path tests/data -prune \) -o \( -name '*.cpp' -o -name '*.h' \) -type f -print0 | sort -z)
bad=0
for f in "${files[@]}"; do
  if ! "$clang_format" --dry-run --Werror "$f" >/dev/null 2>&1; then
    echo "not formatted: $f (run: clang-format -i $f)"
    bad=1
  fi
done
echo "${#files[@]} files checked"
exit $bad
