#!/usr/bin/env bash
# bodysim against real time: 10 simulated seconds of SimpleTank (settle, drive at 1 m/s, spin
# in place, turret pitch and yaw servoed) with `bodysim run`, at several Runge-Kutta-Merson
# accuracies. The peer is the wall clock: ratio = simulated time / CPU time of the whole
# process (user + sys, start-up and CSV included). Prints one Markdown row per accuracy, with
# the integration steps and the drive speed and spin rate reached (to show what accuracy costs).
#   bench/bodysim_realtime.sh [RUNS]          (median of RUNS runs per accuracy, default 5)
#   BODYSIM=build-x/bodysim bench/bodysim_realtime.sh
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bodysim=${BODYSIM:-$here/../build/bodysim}
model=${MODEL:-$here/../../shared/corpus/choreonoid/Tank/SimpleTank.body}
runs=${1:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/s.yaml" <<'YAML'
duration: 10
sample: 0.01
initial: {on_floor: true}
commands:
  - time: 0
    joints:
      TURRET_Y: {target: 0, p: 200, d: 50}
      TURRET_P: {target: 0, p: 200, d: 50}
  - time: 1
    tracks: {TRACK_L: 1.0, TRACK_R: 1.0}
    joints: {TURRET_P: {target: 0.5}}
  - time: 5
    tracks: {TRACK_L: 1.0, TRACK_R: -1.0}
    joints: {TURRET_Y: {target: 1.0}}
  - time: 8
    tracks: {TRACK_L: 0, TRACK_R: 0}
YAML
echo "| accuracy | transition velocity | steps | force evaluations | CPU s (median of $runs) | ratio sim/real | speed at 4.99 s (m/s) | yaw rate at 7.99 s (rad/s) |"
echo "|---|---|---|---|---|---|---|---|"
for setting in "1e-3 0.05" "1e-4 0.05" "1e-5 0.05" "1e-6 0.05" "1e-7 0.05" "1e-5 0.01" "1e-6 0.01"; do
  read -r accuracy vt <<< "$setting"
  times=()
  for ((i = 0; i < runs; i++)); do
    /usr/bin/time -o "$work/time" -f "%U %S" "$bodysim" run "$model" --balance-inertia -q --no-config \
      --accuracy "$accuracy" --transition-velocity "$vt" --scenario "$work/s.yaml" --csv "$work/out.csv" > "$work/stdout" 2> /dev/null
    times+=("$(awk '{print $1 + $2}' "$work/time")")
  done
  median=$(printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
  steps=$(sed -n 's/.* in \([0-9]*\) Runge-Kutta-Merson steps.*/\1/p' "$work/stdout")
  evaluations=$(sed -n 's/.* steps, \([0-9]*\) force evaluations.*/\1/p' "$work/stdout")
  speed=$(awk -F, '$1 == "4.990000" {print $12}' "$work/out.csv")
  yaw=$(awk -F, '$1 == "7.990000" {print $11}' "$work/out.csv")
  ratio=$(awk -v t="$median" 'BEGIN {printf "%.1f", 10 / t}')
  echo "| $accuracy | $vt | $steps | $evaluations | $median | $ratio | $speed | $yaw |"
done
