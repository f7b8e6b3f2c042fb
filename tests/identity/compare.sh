#!/usr/bin/env bash
# Runs export_corpus.sh with the exporters of two builds on each INPUT_DIR and compares the
# outputs byte for byte (files, exit codes, diagnostics). Exit 0 when they are identical.
#
#   tests/identity/compare.sh OLD_BIN_DIR NEW_BIN_DIR WORK_DIR INPUT_DIR...
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
old=$1 new=$2 work=$3
shift 3
status=0
for input in "$@"; do
  name=$(basename "$input")
  rm -rf "$work/old/$name" "$work/new/$name"
  "$here/export_corpus.sh" "$old" "$input" "$work/old/$name"
  "$here/export_corpus.sh" "$new" "$input" "$work/new/$name"
  files=$(find "$work/old/$name" -type f | wc -l)
  if diff -r "$work/old/$name" "$work/new/$name" > "$work/$name.diff"; then
    echo "$name: identical ($files files, $(wc -l < "$work/old/$name/exit_codes.txt") exports)"
  else
    echo "$name: DIFFERENT (see $work/$name.diff)"
    status=1
  fi
done
exit $status
