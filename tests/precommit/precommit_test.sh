#!/usr/bin/env bash
# The bodycheck pre-commit hook, end to end, offline: a temporary git repository with a
# `repo: local` hook installed by Debian's pre-commit; a clean .body commits, a defective one
# is refused with the located message.
#
# usage: precommit_test.sh BODYCHECK TEST_DATA_DIR   (registered in tests/CMakeLists.txt)
set -euo pipefail

bodycheck=$(realpath "$1")
data=$(realpath "$2")
if ! command -v pre-commit >/dev/null; then
  echo "FAIL: pre-commit is not installed (Debian package pre-commit, README command 1)" >&2
  exit 1
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Nothing from the user's environment: own HOME, pre-commit cache and git config.
export HOME="$work/home" PRE_COMMIT_HOME="$work/pre-commit-cache" XDG_CACHE_HOME="$work/cache"
export GIT_CONFIG_NOSYSTEM=1
unset GIT_DIR GIT_WORK_TREE GIT_INDEX_FILE GIT_OBJECT_DIRECTORY GIT_CONFIG_GLOBAL || true
mkdir -p "$HOME"

repo="$work/repo"
git init -q "$repo"
cd "$repo"
git config user.name "bodycheck test"
git config user.email "bodycheck-test@example.invalid"
git config commit.gpgsign false

cat > .pre-commit-config.yaml <<YAML
repos:
  - repo: local
    hooks:
      - id: bodycheck
        name: bodycheck
        entry: $bodycheck
        language: system
        files: \.body$
YAML
pre-commit install

# 1. A clean model goes through.
cp "$data/clean.body" robot.body
git add .pre-commit-config.yaml robot.body
if ! git commit -q -m "clean model" > clean.log 2>&1; then
  cat clean.log
  echo "FAIL: the commit of a clean .body was refused" >&2
  exit 1
fi
grep -q "bodycheck.*Passed" clean.log || { cat clean.log; echo "FAIL: the hook did not run" >&2; exit 1; }

# 2. A defective model is refused, with the located message.
cp "$data/defective.body" broken.body
git add broken.body
if git commit -q -m "defective model" > broken.log 2>&1; then
  cat broken.log
  echo "FAIL: the commit of a defective .body went through" >&2
  exit 1
fi
cat broken.log
expected='broken.body:16:17: error: illegal joint type "hinge" [load-joint-type]'
if ! grep -qF "$expected" broken.log; then
  echo "FAIL: the hook output lacks the located message: $expected" >&2
  exit 1
fi
[ "$(git rev-list --count HEAD)" = 1 ] || { echo "FAIL: expected exactly one commit" >&2; exit 1; }
echo "PASS: clean commit accepted, defective commit refused with the located message"
