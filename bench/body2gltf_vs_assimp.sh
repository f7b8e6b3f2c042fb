#!/usr/bin/env bash
# body2gltf on the largest mesh model of the corpus (UR5-2F85: the UR5 arm and, through a
# SubBody, the Robotiq 2F-85 gripper; 13 Collada files, 10.5 MB) against assimp's own
# `assimp export` (Debian assimp-utils) of the same 13 meshes to GLB, in the same run:
# N interleaved rounds, medians, and the ratio. Times are whole processes.
#
#   bench/body2gltf_vs_assimp.sh [ROUNDS]          (default 11)
#   BODY2GLTF=build-x/body2gltf bench/body2gltf_vs_assimp.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
rounds=${1:-11}
tool=${BODY2GLTF:-build/body2gltf}
model=../shared/corpus/choreonoid/UniversalRobots/UR5-2F85.body
command -v assimp >/dev/null || { echo "assimp (Debian assimp-utils) is not installed" >&2; exit 2; }
[ -x "$tool" ] || { echo "$tool is missing: build it first" >&2; exit 2; }
meshes=(../shared/corpus/choreonoid/UniversalRobots/UR5/{base,shoulder,upperarm,forearm,wrist1,wrist2,wrist3}.dae
        ../shared/corpus/choreonoid/Robotiq/parts/{kinova_robotiq_coupler,robotiq_85_base_link,robotiq_85_finger_link,robotiq_85_finger_tip_link,robotiq_85_inner_knuckle_link,robotiq_85_knuckle_link}.dae)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

now() { date +%s%N; }
median() { sort -n | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

ours=() theirs=() startup=()
for ((i = 0; i < rounds; i++)); do
  t0=$(now)
  "$tool" "$model" -o "$tmp/ur5.glb" -q >/dev/null 2>&1 || [ $? -eq 1 ]
  t1=$(now)
  for m in "${meshes[@]}"; do assimp export "$m" "$tmp/$(basename "$m" .dae).glb" -fglb2 >/dev/null 2>&1; done
  t2=$(now)
  assimp version >/dev/null 2>&1
  t3=$(now)
  ours+=($(( (t1 - t0) / 1000 ))) theirs+=($(( (t2 - t1) / 1000 ))) startup+=($(( (t3 - t2) / 1000 )))
done
o=$(printf '%s\n' "${ours[@]}" | median)
a=$(printf '%s\n' "${theirs[@]}" | median)
s=$(printf '%s\n' "${startup[@]}" | median)
tris=$(python3 - "$tmp/ur5.glb" <<'PY'
import json, struct, sys
b = open(sys.argv[1], "rb").read(); n = struct.unpack_from("<I", b, 12)[0]; d = json.loads(b[20:20 + n])
print(sum(d["accessors"][p["indices"]]["count"] // 3 for m in d["meshes"] for p in m["primitives"]))
PY
)
echo "model: $model ($tris triangles in the GLB, $(stat -c %s "$tmp/ur5.glb") bytes); $rounds rounds"
awk -v o="$o" -v a="$a" -v s="$s" -v n="${#meshes[@]}" 'BEGIN {
  printf "body2gltf (load .body + 13 DAE, tessellate, export, post-process, write): %.1f ms\n", o / 1000
  printf "assimp export of the 13 DAE files to GLB (13 processes):            %.1f ms\n", a / 1000
  printf "  of which process start-up (assimp version x %d):                   %.1f ms\n", n, n * s / 1000
  printf "ratio body2gltf / assimp export:                                    %.2f\n", o / a
  printf "ratio without assimp start-up:                                      %.2f\n", o / (a - n * s)
}'
