#!/usr/bin/env bash
# Time and peak memory of rejecting a "billion laughs" body file (9 levels x 9 aliases, under
# 1 KB, 490 million nodes if expanded), against loading examples/simpletank.body with the
# same binary in the same run: the rejection should cost no more than a small model.
# usage: bench/billion_laughs.sh [BUILD_DIR] [RUNS]
set -euo pipefail
build=${1:-build}
runs=${2:-50}
bomb=$(mktemp --suffix=.body)
trap 'rm -f "$bomb"' EXIT
{
  echo "format: ChoreonoidBody"
  echo "format_version: 2.0"
  echo 'a0: &a0 "lol"'
  for i in 1 2 3 4 5 6 7 8 9; do
    p=$((i - 1))
    echo "a$i: &a$i [*a$p,*a$p,*a$p,*a$p,*a$p,*a$p,*a$p,*a$p,*a$p]"
  done
  echo "links: [{name: A}]"
} > "$bomb"

time_runs() {  # prints the mean wall time in ms of RUNS runs of "$@"
  local start end
  start=$(date +%s%N)
  for _ in $(seq "$runs"); do "$@" > /dev/null 2>&1 || true; done
  end=$(date +%s%N)
  echo "scale=3; ($end - $start) / 1000000 / $runs" | bc
}

bomb_ms=$(time_runs "$build/bodyinfo" "$bomb")
tank_ms=$(time_runs "$build/bodyinfo" examples/simpletank.body)
bomb_kb=$( (/usr/bin/time -f %M "$build/bodyinfo" "$bomb" || true) 2>&1 >/dev/null | tail -1)
tank_kb=$(/usr/bin/time -f %M "$build/bodyinfo" examples/simpletank.body 2>&1 >/dev/null | tail -1)
echo "bomb file: $(wc -c < "$bomb") bytes"
echo "reject bomb:     ${bomb_ms} ms per run, peak ${bomb_kb} KB"
echo "load simpletank: ${tank_ms} ms per run, peak ${tank_kb} KB"
echo "ratio bomb/simpletank: $(echo "scale=2; $bomb_ms / $tank_ms" | bc) (time), $(echo "scale=2; $bomb_kb / $tank_kb" | bc) (memory)"
