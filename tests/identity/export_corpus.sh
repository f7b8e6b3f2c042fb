#!/usr/bin/env bash
# Exports every .body model under INPUT_DIR with the exporters in BIN_DIR (body2urdf, body2mjcf,
# body2gltf) into OUT_DIR, once per option set that changes what is written, and records each
# run's exit code and diagnostics; with the other tools where BIN_DIR has them, also what they
# print for each model (bodyinfo as text and YAML, bodycheck as JSON, bodydiff's canonical text
# and its report against the next model in name order, bodyview's page) and urdf2body's import
# of every .urdf under INPUT_DIR. Two runs of this script, with the exporters of two commits,
# are compared with `diff -r` (compare.sh does both) to show that a refactor left every byte of
# the output as it was.
#
#   tests/identity/export_corpus.sh BIN_DIR INPUT_DIR OUT_DIR
#
# Variants: body2urdf with STL meshes, and with DAE meshes, copies and a package URI;
# body2mjcf as given and with --balance-inertia (more models are written); body2gltf as .gltf
# (visual model, texture files beside it) and as .glb with --both.
set -euo pipefail
bin=$1 input=$2 out=$3
for tool in body2urdf body2mjcf body2gltf; do
  [ -x "$bin/$tool" ] || { echo "export_corpus.sh: no executable $bin/$tool" >&2; exit 2; }
done
mkdir -p "$out"
: > "$out/exit_codes.txt"
printf '<package format="3"><name>corpus</name></package>\n' > "$out/package.xml"

# inspect VARIANT REL TOOL ARGS...: one run of a tool that prints, its standard output and
# diagnostics under OUT_DIR/VARIANT/REL.
inspect() {
  local variant=$1 rel=$2 tool=$3
  shift 3
  [ -x "$bin/$tool" ] || return 0
  local target="$out/$variant/$rel"
  mkdir -p "$(dirname "$target")"
  set +e
  "$bin/$tool" "$@" > "$target.out" 2> "$target.stderr"
  local code=$?
  set -e
  sed -i "s|$out/||g" "$target.out" "$target.stderr"
  echo "$variant $rel $code" >> "$out/exit_codes.txt"
}

# export VARIANT REL EXTENSION TOOL ARGS...: one run, its output under OUT_DIR/VARIANT/REL.
export_one() {
  local variant=$1 rel=$2 extension=$3 tool=$4
  shift 4
  local stem=${rel%.body}
  local dir="$out/$variant/$(dirname "$rel")"
  mkdir -p "$dir"
  local target="$dir/$(basename "$stem").$extension"
  set +e
  "$bin/$tool" -q "$@" "$input/$rel" -o "$target" 2> "$target.stderr"
  local code=$?
  set -e
  # Diagnostics name the output file; the folder differs between the two runs compared.
  sed -i "s|$out/||g" "$target.stderr"
  echo "$variant $rel $code" >> "$out/exit_codes.txt"
}

while IFS= read -r -d '' model; do
  rel=${model#"$input"/}
  export_one urdf-stl "$rel" urdf body2urdf
  # The package root is OUT_DIR (its package.xml), so the URIs are the same in both runs.
  export_one urdf-dae "$rel" urdf body2urdf --mesh-format dae --copy-meshes --package-uri package://corpus
  export_one mjcf "$rel" xml body2mjcf
  export_one mjcf-balanced "$rel" xml body2mjcf --balance-inertia
  export_one gltf "$rel" gltf body2gltf
  export_one glb-both "$rel" glb body2gltf --both
  inspect bodyinfo "$rel" bodyinfo "$model"
  inspect bodyinfo-yaml "$rel" bodyinfo --format yaml "$model"
  inspect bodycheck-json "$rel" bodycheck --format json "$model"
  inspect bodydiff-textconv "$rel" bodydiff --textconv "$model"
  [ -n "${previous:-}" ] && inspect bodydiff-next "$rel" bodydiff --format json "$previous" "$model"
  previous=$model
  if [ -x "$bin/bodyview" ]; then
    # The page embeds three.js (about 1 MB): its digest is kept, not the page.
    inspect bodyview "$rel" bodyview -q "$model" -o "$out/page.html"
    sha256sum < "$out/page.html" > "$out/bodyview/$rel.sha256" 2>/dev/null || true
    rm -f "$out/page.html"
  fi
done < <(find "$input" -name '*.body' -print0 | sort -z)

while IFS= read -r -d '' urdf; do
  rel=${urdf#"$input"/}
  export_one urdf2body "$rel" body urdf2body
done < <(find "$input" -name '*.urdf' -print0 | sort -z)
