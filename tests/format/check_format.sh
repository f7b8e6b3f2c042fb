#!/usr/bin/env bash
# Fails when a C++ file of the project differs from what clang-format (.clang-format) makes
# of it, and lists the files. Usage: check_format.sh CLANG_FORMAT SOURCE_DIR
#
# The files are found, not listed by hand (a folder added later is checked too): in a git
# checkout every tracked or untracked, not ignored, C++ file; elsewhere every C++ file outside
# build trees. tests/data holds inputs, not our code, and is left out in both cases.
set -euo pipefail
clang_format=$1 source_dir=$2
cd "$source_dir"
cxx_names=('*.cpp' '*.cc' '*.cxx' '*.h' '*.hpp')
if git rev-parse --show-toplevel >/dev/null 2>&1 && [ "$(git rev-parse --show-toplevel)" = "$(pwd -P)" ]; then
  mapfile -d '' files < <(git ls-files -z --cached --others --exclude-standard -- "${cxx_names[@]}" \
    ':(exclude)tests/data' | sort -zu)
else
  mapfile -d '' files < <(find . \( -path ./tests/data -o -path './build*' -o -name node_modules -o -name .git \) -prune \
    -o \( -name '*.cpp' -o -name '*.cc' -o -name '*.cxx' -o -name '*.h' -o -name '*.hpp' \) -type f -print0 |
    sed -z 's|^\./||' | sort -z)
fi
bad=0
for f in "${files[@]}"; do
  [ -f "$f" ] || continue  # deleted in the work tree but still tracked
  if ! "$clang_format" --dry-run --Werror "$f" >/dev/null 2>&1; then
    echo "not formatted: $f (run: clang-format -i $f)"
    bad=1
  fi
done
echo "${#files[@]} files checked"
[ "${#files[@]}" -gt 0 ] || { echo "no C++ file found under $source_dir" >&2; exit 1; }
exit $bad
