#!/usr/bin/env bash
# Times bodycheck on SR1.body against check_urdf (liburdfdom-tools) on the same robot's URDF,
# in the same run, and prints the ratio. Whole-process wall time: start-up, parsing and
# checking (bodycheck also imports SR1's meshes and runs every rule).
#
# usage: bench/bodycheck_vs_check_urdf.sh [RUNS]     (from the repository root; default 30)
# env:   BODYCHECK=path/to/bodycheck (default build/bodycheck), SHARED=../shared,
#        BODYCHECK_ARGS=extra options (e.g. --no-meshes to leave out the mesh import)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

runs=${1:-30}
bodycheck=${BODYCHECK:-build/bodycheck}
shared=${SHARED:-../shared}
body="$shared/corpus/choreonoid/SR1/SR1.body"
urdf="$shared/corpus/choreonoid/SR1/SR1.urdf"
for f in "$bodycheck" "$body" "$urdf"; do
  [ -e "$f" ] || { echo "missing: $f" >&2; exit 2; }
done
command -v check_urdf >/dev/null || { echo "check_urdf is missing (apt-get install liburdfdom-tools)" >&2; exit 2; }

# bodycheck exits 1 when it has findings; only 2 (could not check) is a failure here.
# shellcheck disable=SC2206  # BODYCHECK_ARGS is split on purpose, e.g. "--no-meshes"
bodycheck_cmd=("$bodycheck" --quiet ${BODYCHECK_ARGS:-} "$body")
check_urdf_cmd=(check_urdf "$urdf")
"${bodycheck_cmd[@]}" > /dev/null 2>&1 || [ $? -eq 1 ] || { echo "bodycheck failed" >&2; exit 2; }
"${check_urdf_cmd[@]}" > /dev/null 2>&1 || { echo "check_urdf failed" >&2; exit 2; }

if command -v hyperfine >/dev/null; then
  hyperfine --warmup 3 --runs "$runs" -i -N --export-json /tmp/bodycheck_bench.json \
    "${bodycheck_cmd[*]}" "${check_urdf_cmd[*]}"
  python3 - <<'PY'
import json
r = json.load(open("/tmp/bodycheck_bench.json"))["results"]
b, u = r[0]["median"], r[1]["median"]
print(f"bodycheck {b*1e3:.2f} ms, check_urdf {u*1e3:.2f} ms (medians): ratio bodycheck/check_urdf = {b/u:.2f}")
PY
  exit 0
fi

# No hyperfine: N runs each, interleaved, medians in milliseconds.
median() { sort -n | awk '{a[NR]=$1} END {if (NR%2) print a[(NR+1)/2]; else print (a[NR/2]+a[NR/2+1])/2}'; }
for _ in 1 2 3; do "${bodycheck_cmd[@]}" > /dev/null 2>&1 || true; "${check_urdf_cmd[@]}" > /dev/null 2>&1; done
b_times=() u_times=()
for ((i = 0; i < runs; ++i)); do
  t0=$(date +%s%N); "${bodycheck_cmd[@]}" > /dev/null 2>&1 || true; t1=$(date +%s%N)
  "${check_urdf_cmd[@]}" > /dev/null 2>&1; t2=$(date +%s%N)
  b_times+=($(( (t1 - t0) / 1000 ))) u_times+=($(( (t2 - t1) / 1000 )))
done
b=$(printf '%s\n' "${b_times[@]}" | median)
u=$(printf '%s\n' "${u_times[@]}" | median)
awk -v b="$b" -v u="$u" -v n="$runs" 'BEGIN {
  printf "bodycheck  %s: median %.2f ms over %d runs\n", "SR1.body", b / 1000, n
  printf "check_urdf %s: median %.2f ms over %d runs\n", "SR1.urdf", u / 1000, n
  printf "ratio bodycheck/check_urdf = %.2f\n", b / u
}'
