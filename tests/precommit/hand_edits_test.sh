#!/usr/bin/env bash
# The three hand-editing mistakes of issue 40, each through the real bodycheck pre-commit hook
# (`repo: local`, offline, Debian's pre-commit): a typo in a key that changes the model, a
# degree value in a radian file, and a line indented unlike its siblings. Each must refuse the
# commit with exactly one finding (no other error or warning), at the line edited, in words a
# newcomer reads without the spec.
#
# usage: hand_edits_test.sh BODYCHECK   (registered in tests/CMakeLists.txt)
set -euo pipefail

bodycheck=$(realpath "$1")
command -v pre-commit >/dev/null || { echo "FAIL: pre-commit is not installed (README command 1)" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export HOME="$work/home" PRE_COMMIT_HOME="$work/pre-commit-cache" XDG_CACHE_HOME="$work/cache"
export GIT_CONFIG_NOSYSTEM=1
unset GIT_DIR GIT_WORK_TREE GIT_INDEX_FILE GIT_OBJECT_DIRECTORY GIT_CONFIG_GLOBAL || true
mkdir -p "$HOME"
git init -q "$work/repo"
cd "$work/repo"
git config user.name "bodycheck test"
git config user.email "bodycheck-test@example.invalid"
git config commit.gpgsign false
cat > .pre-commit-config.yaml <<YAML
repos:
  - repo: local
    hooks:
      - id: bodycheck
        name: bodycheck
        entry: $bodycheck --git-models
        language: system
        pass_filenames: false
        always_run: true
        require_serial: true
YAML
pre-commit install >/dev/null

# A two-link arm as a newcomer would start from; HEADER is its first lines.
write_arm() {  # write_arm FILE HEADER  (the links follow; line 6 is `links:`)
  printf '%s\n' "$2" > "$1"
  cat >> "$1" <<'BODY'
links:
  - name: BASE
    joint_type: fixed
    mass: 2.0
    inertia: [0.01, 0, 0, 0.01, 0, 0.01]
  - name: ARM
    parent: BASE
    joint_type: revolute
    joint_axis: Z
    joint_range: [-1.5, 1.5]
    mass: 1.0
    inertia: [0.001, 0, 0, 0.001, 0, 0.001]
BODY
}
header2=$'format: ChoreonoidBody\nformat_version: 2.0\nangle_unit: degree\nname: Arm\nroot_link: BASE'
header1=$'format: ChoreonoidBody\nformat_version: 1.0\nangle_unit: radian\nname: Arm\nroot_link: BASE'

write_arm arm.body "$header2"
sed -i 's/joint_range: \[-1.5, 1.5\]/joint_range: [-90, 90]/' arm.body
write_arm radian_arm.body "$header1"
git add .pre-commit-config.yaml arm.body radian_arm.body
git commit -q -m "two clean arms" > clean.log 2>&1 || { cat clean.log; echo "FAIL: the clean arms were refused" >&2; exit 1; }

# mistake FILE SED EXPECTED_LOCATION EXPECTED_WORDS...: the edit must be refused with one
# finding at EXPECTED_LOCATION whose text holds every one of EXPECTED_WORDS.
mistake() {
  local file=$1 edit=$2 at=$3
  shift 3
  cp "$file" "$file.orig"
  sed -i "$edit" "$file"
  git add "$file"
  if git commit -q -m "edit $file" > hook.log 2>&1; then
    cat hook.log
    echo "FAIL: the hook let through: $edit" >&2
    exit 1
  fi
  cat hook.log
  local findings
  findings=$(grep -E '^[^ ]+:[0-9]+:[0-9]+: (fatal error|error|warning):' hook.log || true)
  [ "$(grep -c . <<<"$findings")" = 1 ] ||
    { echo "FAIL: expected one finding for '$edit', got:" >&2; echo "$findings" >&2; exit 1; }
  [[ "$findings" == "$file:$at: "* ]] || { echo "FAIL: expected the finding at $file:$at" >&2; exit 1; }
  local word
  for word in "$@"; do
    grep -qF -- "$word" hook.log || { echo "FAIL: the hook output lacks: $word" >&2; exit 1; }
  done
  mv "$file.orig" "$file"
  git add "$file"
}

# 1. A typo of mass: the link would weigh Choreonoid's default 1 kg.
mistake arm.body 's/^    mass: 1.0/    mas: 6.0/' 16:5 \
  'error: unknown key "mas"' 'did you mean "mass"?' '[load-unknown-model-key]'
# ... and of the range and the axis (the joint would be unlimited, or turn about Z).
mistake arm.body 's/^    joint_range:/    joint_rnage:/' 15:5 'did you mean "joint_range"?' '[load-unknown-model-key]'
mistake arm.body 's/^    joint_axis: Z/    joint_axsi: Y/' 14:5 'did you mean "joint_axis"?' '[load-unknown-model-key]'
# 2. Degrees in a radian file: 14 turns each way.
mistake radian_arm.body 's/joint_range: \[-1.5, 1.5\]/joint_range: [-90, 90]/' 15:18 \
  'is read in radians (angle_unit: radian) but looks like degrees' '[units-range-looks-degree]'
mistake radian_arm.body 's/^    joint_range: \[-1.5, 1.5\]/    max_joint_velocity: 180/' 15:25 \
  'looks like deg/s' '[units-velocity-looks-degree]'
# 3. A key indented one space less than its siblings.
mistake arm.body 's/^    mass: 1.0/   mass: 1.0/' 16:4 \
  'line 16 is indented 3 spaces' 'are indented 4' 'note: libyaml:' '[yaml-syntax]'

[ "$(git rev-list --count HEAD)" = 1 ] || { echo "FAIL: a defective commit went through" >&2; exit 1; }
echo "ok: six hand-editing mistakes refused by the hook, one located finding each"
