#!/bin/bash
# bodydiff in git (docs/tools/bodydiff.md, "bodydiff in git"): as the external diff driver (diff.body.command)
# and as textconv (diff.body.textconv), in a scratch repository.
# usage: bodydiff_git.sh BODYDIFF MODEL WORK_DIR   (MODEL: a .body file without external files)
set -u
bodydiff=$1 model=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 2
export GIT_CONFIG_NOSYSTEM=1 HOME=$work GIT_AUTHOR_NAME=t GIT_AUTHOR_EMAIL=t@example.com \
  GIT_COMMITTER_NAME=t GIT_COMMITTER_EMAIL=t@example.com
git init -q . && echo '*.body diff=body' > .gitattributes
cp "$model" robot.body && git add .gitattributes robot.body && git commit -qm init || exit 2
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
# The two set-ups word for word as bodydiff's manual gives them, bodydiff pointed at the build.
readme=$(dirname "$(realpath "$0")")/../../docs/tools/bodydiff.md
readme_config() { sed -n "s/^git config diff.body.$1 \"bodydiff \(.*\)\"\$/\1/p" "$readme"; }
command_args=$(readme_config command) textconv_args=$(readme_config textconv)
[ -n "$command_args" ] && [ -n "$textconv_args" ] || { echo "docs/tools/bodydiff.md gives no git config diff.body lines"; exit 2; }
driver() { git -c diff.body.command="'$bodydiff' $command_args" diff "$@"; }
textconv() { git -c diff.body.textconv="'$bodydiff' $textconv_args" diff "$@"; }

grep -q '^    mass: 6.0$' robot.body || { echo "the model has no WAIST_P mass line"; exit 2; }
lineno=$(grep -n '^    mass: 6.0$' robot.body | head -1 | cut -d: -f1)

# 1. A reformatting only (spaces, a key respelled): nothing through either.
sed -i 's/^    mass: 6.0$/    mass:    6.00/; s/^    joint_type:/    jointType:/' robot.body
git diff --quiet && fail "the reformatting changed no text"
out=$(driver) || fail "driver exit $? on a reformatting"
[ -z "$out" ] || fail "driver output on a reformatting: $out"
out=$(textconv | grep '^[-+][^-+]') && fail "textconv lines on a reformatting: $out"

# 2. A real change: the mass, at its line on both sides, and the derived total mass.
sed -i 's/^    mass:    6.00$/    mass: 8.5/' robot.body
out=$(driver) || fail "driver exit $? on a change (git needs 0)"
echo "$out" | grep -qx "bodydiff a/robot.body b/robot.body" || fail "no header: $out"
echo "$out" | grep -qx "b/robot.body:$lineno:11: changed: link 'WAIST_P': mass: 6 -> 8.5" || fail "mass change: $out"
echo "$out" | grep -qx "a/robot.body:$lineno:11: note: was 6" || fail "old side: $out"
echo "$out" | grep -q "total_mass (derived)" || fail "no total mass: $out"
[ "$(echo "$out" | grep -c ': changed: ')" = 3 ] || fail "not 3 changes (mass, total mass, centre of mass): $out"
out=$(textconv)
echo "$out" | grep -qx -- "-  mass: 6" && echo "$out" | grep -qx -- "+  mass: 8.5" || fail "textconv: $out"

# 3. The same through GIT_EXTERNAL_DIFF and in git log -p, once committed.
git commit -qam heavier
out=$(GIT_EXTERNAL_DIFF="$bodydiff --git" git log -p --ext-diff -1 --format=%s)
echo "$out" | grep -q "mass: 6 -> 8.5" || fail "git log -p --ext-diff: $out"

# 4. A new model: every link added (old side /dev/null).
cp "$model" arm.body && git add arm.body
out=$(driver --cached) || fail "driver exit $? on an added file"
echo "$out" | grep -q "b/arm.body:[0-9]*:[0-9]*: added: link 'WAIST'" || fail "added file: $out"
[ "$(echo "$out" | grep -c ': added: link ')" -ge 2 ] || fail "added file, links: $out"

# 4b. --git-rev: each file against a revision, for CI (exit 1: differs, 0: same, 2: no such revision).
out=$("$bodydiff" --git-rev HEAD~1 robot.body); code=$?
[ $code = 1 ] || fail "--git-rev HEAD~1 exit $code"
echo "$out" | grep -qx "robot.body:$lineno:11: changed: link 'WAIST_P': mass: 6 -> 8.5" || fail "--git-rev: $out"
echo "$out" | grep -qx "HEAD~1:robot.body:$lineno:11: note: was 6" || fail "--git-rev old side: $out"
out=$("$bodydiff" --git-rev HEAD robot.body) || fail "--git-rev HEAD exit $? on an unchanged file"
[ -z "$out" ] || fail "--git-rev HEAD output: $out"
"$bodydiff" --git-rev no-such-rev robot.body 2>/dev/null; [ $? = 2 ] || fail "--git-rev of no revision: not exit 2"
out=$("$bodydiff" --git-rev HEAD arm.body)
echo "$out" | grep -q "arm.body:[0-9]*:[0-9]*: added: link 'WAIST'" || fail "--git-rev on a new file: $out"

# 4c. Only git's own "not in REV" (or "not in the index") means new (issue 34): an absolute
#     path is the same file, and anything git cannot read is exit 2 with git's message.
mkdir -p sub untracked && touch sub/.keep && cp "$model" untracked/u.body
out=$("$bodydiff" --git-rev HEAD~1 "$PWD/robot.body"); code=$?
[ $code = 1 ] && echo "$out" | grep -q "mass: 6 -> 8.5" && ! echo "$out" | grep -q "added: link" ||
  fail "--git-rev of an absolute path: exit $code: $out"
rev_error() {  # rev_error WHAT WORDS ARGS...: exit 2 and git's words on stderr, nothing on stdout
  local what=$1 words=$2; shift 2
  out=$("$@" 2>err.txt); code=$?
  [ $code = 2 ] && [ -z "$out" ] && grep -q -- "$words" err.txt || fail "$what: exit $code, $out $(cat err.txt)"
}
rev_error "--git-rev of ../ outside the repository" "outside repository" \
  "$bodydiff" --git-rev HEAD "../$(basename "$PWD")/robot.body"
rev_error "--git-rev of a mistyped file" "does not exist in 'HEAD'" "$bodydiff" --git-rev HEAD robto.body
rev_error "--git-rev of an untracked folder" "a folder" "$bodydiff" --git-rev HEAD untracked
rev_error "--staged of a mistyped file" "neither on disk nor in the index" "$bodydiff" --staged robto.body
# A blob larger than the file-size limit is refused as a file on disk would be, and git's output
# is not read past it (issue 35: the git reader was unbounded).
rev_error "--git-rev of a blob over --max-file-size" "robot.body at HEAD is larger than the limit of 100 bytes" \
  "$bodydiff" --max-file-size 100 --git-rev HEAD robot.body
cp robot.body big.body && git add big.body  # new in the index: only the index's blob is read
rev_error "--staged of a blob over --max-file-size" "big.body in the index is larger than the limit of 100 bytes" \
  "$bodydiff" --max-file-size 100 --staged big.body
git rm -q --cached big.body && rm big.body
out=$(cd sub && "$bodydiff" --git-rev HEAD~1 ../robot.body); code=$?
[ $code = 1 ] && echo "$out" | grep -q "mass: 6 -> 8.5" || fail "--git-rev of ../robot.body from sub: exit $code: $out"
outside=$(mktemp -d) && cp "$model" "$outside/m.body"
out=$(cd "$outside" && "$bodydiff" --staged m.body 2>&1); code=$?
[ $code = 2 ] && echo "$out" | grep -q "not a git repository" || fail "--staged outside a repository: exit $code: $out"
rm -rf "$outside" untracked

# 4d. A file whose name begins with '-' (issue 34): through both set-ups of the manual, git diff works.
cp "$model" ./-q.body && git add -- -q.body && git commit -qm dash
sed -i 's/^    mass: 6.0$/    mass: 7.25/' ./-q.body
out=$(driver -- -q.body 2>&1); code=$?
[ $code = 0 ] && echo "$out" | grep -q "b/-q.body:$lineno:11: changed: link 'WAIST_P': mass: 6 -> 7.25" ||
  fail "driver on -q.body: exit $code: $out"
out=$(textconv -- -q.body 2>&1); code=$?
[ $code = 0 ] && echo "$out" | grep -qx -- "+  mass: 7.25" || fail "textconv on -q.body: exit $code: $out"
out=$("$bodydiff" --git-rev HEAD -- -q.body); code=$?
[ $code = 1 ] && echo "$out" | grep -q "mass: 6 -> 7.25" || fail "--git-rev HEAD -- -q.body: exit $code: $out"
cp "$model" ./-q.body

# 5. A model that cannot be loaded: git stops with the driver's exit 2 and its message.
echo "links: [ {" > robot.body
driver >/dev/null 2>err.txt && fail "driver exit 0 on a broken model"
grep -q "robot.body" err.txt || fail "no located error: $(cat err.txt)"
echo "$failures failures"
[ "$failures" = 0 ]
