#!/usr/bin/env bash
# Opt-in conformance of wrapper body files around URDFs (issue 44): wraps each URDF in a one-line
# body file (`model_file: X.urdf`), makes a reference of that wrapper with Choreonoid's own loaders
# (choreonoid_dump built with Choreonoid's URDF loader, see choreonoid_dump/README.md), and
# compares bodyinfo on the same wrapper with it, every field (choreonoid_refs.py).
# Run by hand: it needs a Choreonoid build, so it is not registered in ctest and never runs in CI.
#
# usage: choreonoid_urdf.sh CHOREONOID_DUMP BODYINFO OUT_DIR [PATH...]
#   PATH     a URDF file (its folder is copied, for its meshes) or a folder (every *.urdf and
#            *.urdf.gz in it); default: tests/data/urdf_choreonoid and the corpus SR1.urdf
#   OUT_DIR  OUT_DIR/models/<n>-<name>/ the copies and wrappers, OUT_DIR/ref/ the references,
#            OUT_DIR/outcomes.txt one line per wrapper and the count of each outcome
# Environment: STRIP_MESHES=1 removes every <visual> and <collision> holding a <mesh> from the
# copies first (public URDFs often name meshes of ROS packages that are not there: Choreonoid
# refuses those files, and the rest of the model can still be compared).
# Exit status: 0 when every wrapper matches or both refuse it, 1 otherwise, 2 on a usage error.
set -euo pipefail

if [ $# -lt 3 ]; then
  sed -n '8,16p' "$0" >&2
  exit 2
fi
dumper=$1 bodyinfo=$2 out=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
[ $# -gt 0 ] || set -- "$here/../data/urdf_choreonoid" "$here/../../../shared/corpus/choreonoid/SR1/SR1.urdf"
for tool in "$dumper" "$bodyinfo"; do
  [ -x "$tool" ] || { echo "not an executable: $tool" >&2; exit 2; }
done
mkdir -p "$out/models" "$out/ref" && out=$(cd "$out" && pwd)

# The copies: one folder per PATH; a file brings its folder along and is the only URDF wrapped.
urdfs=()
n=0
for path in "$@"; do
  n=$((n + 1))
  if [ -d "$path" ]; then
    dest=$out/models/$n-$(basename "$path")
    rm -rf "$dest" && cp -r "$path" "$dest"
    find "$dest" -name '*.urdf.gz' -exec gunzip -f {} +
    while IFS= read -r -d '' urdf; do urdfs+=("$urdf"); done < <(find "$dest" -name '*.urdf' -type f -print0 | sort -z)
  elif [ -f "$path" ]; then
    dest=$out/models/$n-$(basename "$(dirname "$path")")
    rm -rf "$dest" && cp -r "$(dirname "$path")" "$dest"
    urdfs+=("$dest/$(basename "$path")")
  else
    echo "no such file or folder: $path" >&2
    exit 2
  fi
done
if [ "${STRIP_MESHES:-0}" = 1 ]; then
  python3 - "${urdfs[@]}" <<'EOF'
import re, sys
for path in sys.argv[1:]:
    with open(path, errors="replace") as f:
        text = f.read()
    text = re.sub(r"<(visual|collision)\b[^>]*?(?<!/)>(?:(?!</\1>).)*?<mesh\b(?:(?!</\1>).)*?</\1>", "", text,
                  flags=re.S)
    with open(path, "w") as f:
        f.write(text)
EOF
fi

# One wrapper per URDF (X.body, or X.urdf.body beside a body file of that name) and its reference.
wrappers=()
loaded=0
for urdf in "${urdfs[@]}"; do
  name=$(basename "$urdf")
  wrapper=${urdf%.urdf}.body
  line="model_file: \"$name\""
  if [ -e "$wrapper" ] && ! grep -qxF -e "$line" -e "model_file: $name" "$wrapper"; then
    wrapper=$urdf.body
  fi
  [ -e "$wrapper" ] || printf '%s\n' "$line" >"$wrapper"
  rel=${wrapper#"$out/models/"}
  ref=$out/ref/${rel%.body}.ref.yaml
  mkdir -p "$(dirname "$ref")"
  status=0
  timeout 120 "$dumper" "$wrapper" >"$ref" 2>/dev/null || status=$?
  if [ "$status" -eq 0 ]; then
    loaded=$((loaded + 1))
  elif [ "$status" -ne 1 ]; then  # a crash or a hang is a refusal, with the reason
    printf 'loaded: false\nmessages: "choreonoid_dump failed with status %s"\n' "$status" >"$ref"
  fi
  wrappers+=("$rel")
done

status=0
python3 "$here/choreonoid_refs.py" "$bodyinfo" "$out/models" "$out/ref" "${wrappers[@]}" \
  >"$out/outcomes.txt" || status=$?
cat "$out/outcomes.txt"
echo "Choreonoid loads $loaded of ${#wrappers[@]} wrappers; output: $out"
exit "$status"
