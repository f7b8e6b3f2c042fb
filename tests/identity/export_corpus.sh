#!/usr/bin/env bash
# Exports every corpus model with one body2urdf binary into OUT_DIR, once per option set that
# changes what is written (STL meshes, DAE meshes with copies and a package URI), and records
# each run's exit code. Two runs of this script, with the body2urdf of two commits, are
# compared with `diff -r` to show that a refactor left every byte of the output as it was.
#
#   tests/identity/export_corpus.sh BODY2URDF CORPUS_DIR OUT_DIR
set -euo pipefail
body2urdf=$1 corpus=$2 out=$3
mkdir -p "$out"
: > "$out/exit_codes.txt"
while IFS= read -r -d '' model; do
  rel=${model#"$corpus"/}
  stem=${rel%.body}
  for variant in stl dae; do
    dir="$out/$variant/$(dirname "$rel")"
    mkdir -p "$dir"
    args=()
    [ "$variant" = dae ] && args=(--mesh-format dae --copy-meshes --package-uri package://corpus)
    [ "$variant" = dae ] && [ ! -e "$out/dae/package.xml" ] && mkdir -p "$out/dae" && printf '<package format="3"><name>corpus</name></package>\n' > "$out/dae/package.xml"
    set +e
    "$body2urdf" -q "${args[@]}" "$model" -o "$dir/$(basename "$stem").urdf" 2>/dev/null
    code=$?
    set -e
    echo "$variant $rel $code" >> "$out/exit_codes.txt"
  done
done < <(find "$corpus" -name '*.body' -print0 | sort -z)
