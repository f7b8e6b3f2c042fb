#!/usr/bin/env bash
# The bodydiff pre-commit stage, end to end, offline, with Debian's pre-commit: a temporary git
# repository whose `repo: local` hook is the `bodydiff` entry of .pre-commit-hooks.yaml as
# written there (only the program's path replaced by the built one). The first commit shows the
# model's links added; a staged mass change is printed at its line on both sides and the commit
# goes through; a reformatting prints nothing; an unstaged edit is not shown; a staged model that
# cannot be loaded (invalid YAML) stops the commit with the located error.
#
# usage: bodydiff_stage_test.sh BODYDIFF HOOKS_YAML MODEL   (registered in tests/CMakeLists.txt)
set -euo pipefail

bodydiff=$(realpath "$1")
hooks=$(realpath "$2")
model=$(realpath "$3")
if ! command -v pre-commit >/dev/null; then
  echo "FAIL: pre-commit is not installed (Debian package pre-commit, README command 1)" >&2
  exit 1
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export HOME="$work/home" PRE_COMMIT_HOME="$work/pre-commit-cache" XDG_CACHE_HOME="$work/cache"
export GIT_CONFIG_NOSYSTEM=1
unset GIT_DIR GIT_WORK_TREE GIT_INDEX_FILE GIT_OBJECT_DIRECTORY GIT_CONFIG_GLOBAL || true
mkdir -p "$HOME"

repo="$work/repo"
git init -q "$repo"
cd "$repo"
git config user.name "bodydiff test"
git config user.email "bodydiff-test@example.invalid"
git config commit.gpgsign false

# The hook as defined for users, its program pointed at the build.
python3 - "$hooks" "$bodydiff" > .pre-commit-config.yaml <<'PY'
import sys, yaml
hooks, program = sys.argv[1:3]
hook = next(h for h in yaml.safe_load(open(hooks)) if h["id"] == "bodydiff")
assert hook["entry"].split()[0] == "bodydiff", hook["entry"]
hook["entry"] = program + hook["entry"][len("bodydiff"):]
print(yaml.safe_dump({"repos": [{"repo": "local", "hooks": [hook]}]}, sort_keys=False))
PY
pre-commit install >/dev/null
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# 1. The first commit (no HEAD yet): the model is new, every link added; the commit goes through.
cp "$model" robot.body
git add .pre-commit-config.yaml robot.body
git commit -q -m "first model" > first.log 2>&1 || { cat first.log; fail "the first commit was refused"; }
grep -q "^bodydiff.*Passed" first.log || fail "the stage did not run on the first commit: $(cat first.log)"
grep -q "^robot.body:[0-9]*:[0-9]*: added: link 'WAIST': root, free joint$" first.log ||
  fail "the first commit does not show the links added: $(cat first.log)"

grep -q '^    mass: 6.0$' robot.body || { echo "the model has no WAIST_P mass line" >&2; exit 2; }
lineno=$(grep -n '^    mass: 6.0$' robot.body | head -1 | cut -d: -f1)

# 2. A staged mass change is printed at its line on both sides, with the derived total mass;
#    an unstaged edit of another link is not; the commit goes through.
sed -i 's/^    mass: 6.0$/    mass: 8.5/' robot.body
git add robot.body
sed -i 's/^    mass: 13.0$/    mass: 14.0/' robot.body
git commit -q -m "heavier waist" > change.log 2>&1 || { cat change.log; fail "a commit with a change was refused"; }
grep -qx "robot.body:$lineno:11: changed: link 'WAIST_P': mass: 6 -> 8.5" change.log || fail "no mass change: $(cat change.log)"
grep -qx "HEAD:robot.body:$lineno:11: note: was 6" change.log || fail "no old side: $(cat change.log)"
grep -q "changed: model: total_mass (derived): 130.8 -> 133.3" change.log || fail "no total mass: $(cat change.log)"
grep -q "mass: 13 -> 14" change.log && fail "the unstaged edit was shown: $(cat change.log)"
[ "$(git rev-list --count HEAD)" = 2 ] || fail "expected two commits"
git checkout -q -- robot.body

# 3. A reformatting only (a key respelled, spaces): the stage passes and prints nothing.
sed -i 's/^    mass: 8.5$/    mass:   8.50/; s/^    joint_type:/    jointType:/' robot.body
git add robot.body
git commit -q -m "reformat" > reformat.log 2>&1 || { cat reformat.log; fail "a reformatting was refused"; }
grep -q "^bodydiff.*Passed" reformat.log || fail "the stage did not run: $(cat reformat.log)"
grep -q "robot.body:" reformat.log && fail "a reformatting printed changes: $(cat reformat.log)"

# 4. A staged model that cannot be loaded (a flow sequence left open) stops the commit with the
#    located error.
sed -i "${lineno}s/.*/    mass: [ 8.5/" robot.body
git add robot.body
if git commit -q -m "broken" > broken.log 2>&1; then fail "a broken model was committed: $(cat broken.log)"; fi
grep -q "^bodydiff.*Failed" broken.log || fail "the stage did not fail: $(cat broken.log)"
grep -Eq "^robot.body:[0-9]+:[0-9]+: (error|fatal error): .*\[yaml-" broken.log || fail "no located error: $(cat broken.log)"
[ "$(git rev-list --count HEAD)" = 3 ] || fail "expected three commits"

[ "$failures" = 0 ] || exit 1
echo "PASS: the bodydiff stage shows new links, a staged change at its lines, nothing for a reformatting, and stops a broken model"
