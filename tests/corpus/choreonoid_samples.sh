#!/usr/bin/env bash
# Opt-in conformance over every .body file of Choreonoid's sample/ and share/model/: makes
# references with Choreonoid's own loader (choreonoid_dump, see choreonoid_dump/README.md), then
# compares bodyinfo with them (shared/tools/conformance.py). Run by hand: it needs a Choreonoid
# checkout and build, so it is not registered in ctest and never runs in CI.
#
# usage: choreonoid_samples.sh CHOREONOID CHOREONOID_DUMP BODYINFO [OUT_DIR]
#   CHOREONOID       a Choreonoid source tree, or a (bare) git mirror of one (its HEAD is used)
#   CHOREONOID_DUMP  the built dumper (tests/corpus/choreonoid_dump)
#   BODYINFO         the bodyinfo to check
#   OUT_DIR          where the models and references go (default: a new temporary folder);
#                    OUT_DIR/ref/<path>.ref.yaml, OUT_DIR/conformance.txt
# Environment: CONFORMANCE overrides the comparer (default ../shared/tools/conformance.py
# beside this checkout).
# Exit status: 0 when every model Choreonoid loads matches, 1 when one does not, 2 on a usage
# or setup error.
set -euo pipefail

if [ $# -lt 3 ] || [ $# -gt 4 ]; then
  sed -n '7,13p' "$0" >&2
  exit 2
fi
choreonoid=$1 dumper=$2 bodyinfo=$3
out=${4:-$(mktemp -d "${TMPDIR:-/tmp}/choreonoid_samples.XXXXXX")}
mkdir -p "$out" && out=$(cd "$out" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
conformance=${CONFORMANCE:-$here/../../../shared/tools/conformance.py}
for tool in "$dumper" "$bodyinfo"; do
  [ -x "$tool" ] || { echo "not an executable: $tool" >&2; exit 2; }
done
[ -f "$conformance" ] || { echo "conformance.py not found at $conformance (set CONFORMANCE)" >&2; exit 2; }

# The models: straight from a source tree, or extracted from a git mirror's HEAD.
if [ -d "$choreonoid/sample" ] && [ -d "$choreonoid/share/model" ]; then
  models=$(cd "$choreonoid" && pwd)
elif git -C "$choreonoid" rev-parse --verify -q HEAD >/dev/null 2>&1; then
  models=$out/models
  mkdir -p "$models"
  git -C "$choreonoid" archive HEAD -- sample share/model | tar x -C "$models"
  echo "models: $(git -C "$choreonoid" rev-parse --short HEAD) of $choreonoid"
else
  echo "neither a Choreonoid source tree (sample/, share/model/) nor a git repository: $choreonoid" >&2
  exit 2
fi

# One reference per file, at the file's relative path; a refusal is kept as loaded: false.
refs=$out/ref
total=0 loaded=0
while IFS= read -r -d '' body; do
  rel=${body#"$models"/}
  ref=$refs/${rel%.body}.ref.yaml
  mkdir -p "$(dirname "$ref")"
  total=$((total + 1))
  # The dumper exits 1 on a refusal, with the YAML still written; anything else (a crash, a
  # hang) becomes a refusal with the reason, so every file has a reference.
  status=0
  timeout 120 "$dumper" "$body" >"$ref" 2>"$ref.err" || status=$?
  if [ "$status" -eq 0 ]; then
    loaded=$((loaded + 1))
  elif [ "$status" -ne 1 ]; then
    printf 'loaded: false\nmessages: "choreonoid_dump failed with status %s"\n' "$status" >"$ref"
  fi
  [ -s "$ref.err" ] || rm -f "$ref.err"
done < <(find "$models/sample" "$models/share/model" -name '*.body' -type f -print0 | sort -z)

status=0
python3 "$conformance" "$bodyinfo" "$models" "$refs" >"$out/conformance.txt" || status=$?
cat "$out/conformance.txt"
echo "Choreonoid loads $loaded of $total .body files; the rest are refused (loaded: false in $refs)"
for root in sample share/model; do
  files=$(find "$refs/$root" -name '*.ref.yaml' | wc -l)
  refused=$(grep -rl --include='*.ref.yaml' '^loaded: false' "$refs/$root" | wc -l)
  differ=$(grep -c "^$root/" "$out/conformance.txt" || true)
  echo "$root/: $files files, Choreonoid loads $((files - refused)), bodyinfo matches $((files - refused - differ))"
done
echo "output: $out"
[ "$status" -le 1 ] || exit 2
exit "$status"
