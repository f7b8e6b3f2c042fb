#!/usr/bin/env bash
# bodycheck --format sarif, checked by Microsoft's SARIF Multitool (`validate`). Passes only
# when the Multitool reports no errors and no warnings (its notes are allowed).
#
# usage: validate_sarif.sh BODYCHECK TEST_DATA_DIR NPM_PREFIX
# The Multitool comes from README command 2: npm install --prefix build/npm @microsoft/sarif-multitool
set -euo pipefail

bodycheck=$(realpath "$1")
data=$(realpath "$2")
npm_prefix=$3
multitool="$npm_prefix/node_modules/.bin/sarif-multitool"
if [ ! -x "$multitool" ]; then
  echo "FAIL: the SARIF Multitool is missing at $multitool;" \
       "install it with: npm install --prefix $npm_prefix @microsoft/sarif-multitool" >&2
  exit 1
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export HOME="$work/home" DOTNET_CLI_TELEMETRY_OPTOUT=1
mkdir -p "$HOME"
cp "$data/warning.body" "$work/outside.body"  # outside the working dir: an absolute file:// URI

status=0
check() {  # check NAME BODYCHECK-ARGS...
  local name=$1
  shift
  local log="$work/$name.sarif"
  local rc=0
  (cd "$data" && "$bodycheck" --format sarif "$@") > "$log" || rc=$?
  if [ "$rc" -gt 2 ]; then echo "FAIL: bodycheck exited $rc for $name" >&2; status=1; return; fi
  local out
  out=$("$multitool" validate "$log" 2>&1) || { echo "$out"; echo "FAIL: the Multitool failed on $name" >&2; status=1; return; }
  if grep -Eq '(^|[ :])(error|warning) [A-Z]+[0-9]+' <<< "$out" || ! grep -q "Analysis completed successfully" <<< "$out"; then
    echo "$out"
    echo "FAIL: $name: the Multitool reports errors or warnings" >&2
    status=1
    return
  fi
  echo "ok: $name ($(grep -c '"ruleId"' "$log" || true) results)"
}

check all-kinds defective.body warning.body suppressed.body clean.body alias.body unloadable.body "$work/outside.body"
check clean clean.body
check directory .
check werror-quiet --werror --quiet configured
# Fix-its as SARIF `fixes` (safe, upgrade and unsafe ones; one with 40 edits in one fix).
check fix-its ../fix/legacy.body ../fix/radian_v1.body ../fix/include/main.body
exit $status
