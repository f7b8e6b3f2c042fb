#!/usr/bin/env bash
# body -> URDF -> body on the corpus, judged by the shared conformance script against
# Choreonoid's own loader values: every model that body2urdf exports without reporting a loss
# must come back from urdf2body with the reference's links, joints, masses, frames and boxes.
# Usage: corpus_round_trip.sh BODY2URDF URDF2BODY BODYINFO CORPUS_DIR (holding choreonoid/,
# reference/) CONFORMANCE_PY
set -euo pipefail
body2urdf=$1 urdf2body=$2 bodyinfo=$3 corpus=$4 conformance=$5
# Known differences, each with its reason; they are left out of the comparison (and printed).
declare -A known=(
  ["misc/HandyRockDrill.body"]="PUSHER is a prismatic joint without joint_id; URDF cannot say 'no id', and urdf2body numbers every movable joint in document order (body2urdf does not report it)"
)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
: > "$work/lossless.txt"
exported=0 lossless=0
while IFS= read -r -d '' ref; do
  rel=${ref#"$corpus/reference/"}
  rel=${rel%.ref.yaml}.body
  grep -q '^loaded: true' "$ref" || continue
  mkdir -p "$work/out/$(dirname "$rel")"
  urdf="$work/out/${rel%.body}.urdf"
  # --floating-base keeps the root's joint type and initial pose; --copy-meshes puts every mesh
  # beside the URDF, so that the re-imported body refers to files of this export.
  status=0
  "$body2urdf" "$corpus/choreonoid/$rel" -o "$urdf" --floating-base --copy-meshes > "$work/log" 2>&1 || status=$?
  [ "$status" -le 1 ] || continue
  exported=$((exported + 1))
  grep -q '\[export-loss\]' "$work/log" && continue
  if [ -n "${known[$rel]:-}" ]; then
    echo "left out: $rel: ${known[$rel]}"
    continue
  fi
  lossless=$((lossless + 1))
  if ! "$urdf2body" "$urdf" -o "$work/out/$rel" > "$work/log" 2>&1; then
    echo "urdf2body failed on the export of $rel:"
    cat "$work/log"
    exit 1
  fi
  echo "$rel" >> "$work/lossless.txt"
done < <(find "$corpus/reference" -name '*.ref.yaml' -print0 | sort -z)
echo "$exported models exported, $lossless without a reported loss"
[ "$lossless" -gt 0 ]
python3 "$conformance" "$bodyinfo" "$work/out" "$corpus/reference" --only "$work/lossless.txt"
