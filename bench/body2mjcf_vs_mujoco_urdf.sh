#!/usr/bin/env bash
# Times, in the same run, the road from a Choreonoid model to a compiled MuJoCo model through
# body2mjcf (body2mjcf SR1.body, then MuJoCo 2.2.2 compiles the MJCF it wrote) against MuJoCo
# compiling the hand-written SR1.urdf of the same robot directly (its URDF importer), and
# prints the ratio. Whole-process wall times; the MuJoCo side is a small C program compiled
# here that calls mj_loadXML on its argument (MJCF or URDF) and nothing else.
#
# usage: bench/body2mjcf_vs_mujoco_urdf.sh [RUNS]     (from the repository root; default 30)
# env:   BODY2MJCF=path/to/body2mjcf (default build/body2mjcf), SHARED=../shared
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

runs=${1:-30}
body2mjcf=${BODY2MJCF:-build/body2mjcf}
shared=${SHARED:-../shared}
body="$shared/corpus/choreonoid/SR1/SR1.body"
urdf="$shared/corpus/choreonoid/SR1/SR1.urdf"
for f in "$body2mjcf" "$body" "$urdf"; do
  [ -e "$f" ] || { echo "missing: $f" >&2; exit 2; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cat > "$work/mjload.c" <<'C'
#include <mujoco/mujoco.h>
#include <stdio.h>
int main(int argc, char** argv) {
  char error[1000] = "";
  mjModel* m = argc > 1 ? mj_loadXML(argv[1], NULL, error, sizeof error) : NULL;
  if (!m) { fprintf(stderr, "mj_loadXML: %s\n", error); return 1; }
  mj_deleteModel(m);
  return 0;
}
C
cc -O2 "$work/mjload.c" -o "$work/mjload" -lmujoco
mjload="$work/mjload"
out="$work/out/SR1.xml"

ours() { "$body2mjcf" -q "$body" -o "$out" 2>/dev/null || [ $? -eq 1 ]; "$mjload" "$out"; }
theirs() { "$mjload" "$urdf"; }
ours > /dev/null || { echo "body2mjcf + mj_loadXML failed" >&2; exit 2; }
theirs > /dev/null || { echo "mj_loadXML SR1.urdf failed" >&2; exit 2; }

# Warm-up, then N runs each, interleaved, medians in milliseconds.
median() { sort -n | awk '{a[NR]=$1} END {if (NR%2) print a[(NR+1)/2]; else print (a[NR/2]+a[NR/2+1])/2}'; }
for _ in 1 2 3; do ours > /dev/null; theirs > /dev/null; done
o_times=() t_times=() c_times=()
for ((i = 0; i < runs; ++i)); do
  t0=$(date +%s%N); "$body2mjcf" -q "$body" -o "$out" > /dev/null 2>&1 || true; t1=$(date +%s%N)
  "$mjload" "$out" > /dev/null; t2=$(date +%s%N)
  theirs > /dev/null; t3=$(date +%s%N)
  o_times+=($(( (t2 - t0) / 1000 ))) c_times+=($(( (t2 - t1) / 1000 ))) t_times+=($(( (t3 - t2) / 1000 )))
done
o=$(printf '%s\n' "${o_times[@]}" | median)
c=$(printf '%s\n' "${c_times[@]}" | median)
t=$(printf '%s\n' "${t_times[@]}" | median)
awk -v o="$o" -v c="$c" -v t="$t" -v n="$runs" 'BEGIN {
  printf "body2mjcf SR1.body + mj_loadXML of its MJCF: median %.2f ms over %d runs (of which mj_loadXML %.2f ms)\n", o / 1000, n, c / 1000
  printf "mj_loadXML SR1.urdf:                         median %.2f ms over %d runs\n", t / 1000, n
  printf "ratio (body2mjcf + MuJoCo) / (MuJoCo on the URDF) = %.2f\n", o / t
}'
