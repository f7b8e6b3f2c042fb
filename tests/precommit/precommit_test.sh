#!/usr/bin/env bash
# The bodycheck pre-commit hook, end to end, offline: a temporary git repository with a
# `repo: local` hook installed by Debian's pre-commit, configured as .pre-commit-hooks.yaml
# says: a clean .body commits; a defective one is refused with the located message; deleting a
# mesh a model uses, or breaking a .body file that a model includes, is refused too; and one
# bodycheck run prints one summary for all models.
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
        entry: $bodycheck --git-models
        language: system
        pass_filenames: false
        always_run: true
        require_serial: true
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
git reset -q HEAD broken.body && rm broken.body

# 3. A model with a mesh and an included arm: committed clean.
mkdir -p meshes parts
cat > meshes/plate.stl <<'STL'
solid plate
facet normal 0 0 1
outer loop
vertex 0 0 0
vertex 0.1 0 0
vertex 0 0.1 0
endloop
endfacet
endsolid plate
STL
cat > parts/arm.body <<'BODY'
format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
name: Arm
root_link: ARM
links:
  - name: ARM
    joint_type: fixed
    mass: 0.5
    inertia: [0.001, 0, 0, 0.001, 0, 0.001]
BODY
cat > cart.body <<'BODY'
format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
name: Cart
root_link: BASE
links:
  - name: BASE
    joint_type: free
    mass: 1
    inertia: [0.01, 0, 0, 0.01, 0, 0.01]
    elements:
      - type: Shape
        geometry: { type: Resource, uri: meshes/plate.stl }
  - type: SubBody
    uri: parts/arm.body
    parent: BASE
BODY
git add meshes parts cart.body
if ! git commit -q -m "cart with a mesh and an included arm" > cart.log 2>&1; then
  cat cart.log
  echo "FAIL: the commit of a clean model with a mesh and an include was refused" >&2
  exit 1
fi

# 4. Deleting the mesh (no .body file staged) is refused at the model's uri: value.
git rm -q meshes/plate.stl
if git commit -q -m "delete the mesh" > deleted.log 2>&1; then
  cat deleted.log
  echo "FAIL: deleting a mesh that cart.body uses went through" >&2
  exit 1
fi
grep -q "cart.body:13:42: error: .*\[mesh-file-missing\]" deleted.log ||
  { cat deleted.log; echo "FAIL: no located mesh-file-missing error for cart.body" >&2; exit 1; }
# One serial run, one summary, for every model in the index (cart.body, parts/arm.body, robot.body).
summaries=$(grep -c "files checked" deleted.log || true)
[ "$summaries" = 1 ] || { cat deleted.log; echo "FAIL: expected one bodycheck summary, got $summaries" >&2; exit 1; }
grep -q "bodycheck: 3 files checked" deleted.log || { cat deleted.log; echo "FAIL: expected 3 models checked" >&2; exit 1; }
git reset -q HEAD meshes/plate.stl && git checkout -q -- meshes/plate.stl

# 5. Breaking only the included file is refused, for the model that includes it as well.
sed -i 's/joint_type: fixed/joint_type: hinge/' parts/arm.body
git add parts/arm.body
if git commit -q -m "break the included arm" > include.log 2>&1; then
  cat include.log
  echo "FAIL: breaking an included .body file went through" >&2
  exit 1
fi
grep -q "parts/arm.body:8:17: error: illegal joint type \"hinge\"" include.log ||
  { cat include.log; echo "FAIL: no located error in the included file" >&2; exit 1; }
[ "$(git rev-list --count HEAD)" = 2 ] || { echo "FAIL: expected exactly two commits" >&2; exit 1; }
echo "PASS: clean commits accepted; defective model, deleted mesh and broken include refused with located messages"
