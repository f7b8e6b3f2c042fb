#!/usr/bin/env bash
# Every option a tool's --help lists is in its manual (docs/tools/TOOL.md, or the page of the
# options every tool shares, docs/tools/README.md), and --help shows no internals (an enum's
# numbers, CLI11's "value in {a->0} OR {0}", a flag's default in braces, "--fix{safe}", or a
# validator with no value before it, " :{safe,geometry}"). A value --help shows unbracketed
# after an option ("--opt VALUE") must be required: `TOOL --opt --help` fails (issue 47:
# --mass-from-geometry DENSITY looked required and was not). Enumerates the options of each
# tool given, and of each bodysim subcommand.
#
# usage: options_in_manual.sh docs/tools TOOL...   (registered in tests/CMakeLists.txt)
set -euo pipefail
manual_dir=$1
shift
failed=0
checked=0
check_help() {
  local name=$1 help=$2 manual=$3
  shift 3  # the rest: the command that printed the help
  if grep -nE 'ENUM|->|OR \{|--[A-Za-z0-9-]+\{| :\{' <<<"$help"; then
    echo "FAIL: $name --help shows internals (above)" >&2
    failed=1
  fi
  local shown
  for shown in $(grep -oE -- '^ +(-[A-Za-z], ?)?--[A-Za-z][A-Za-z0-9-]* [A-Z][A-Z0-9_]*([: ]|$)' <<<"$help" | grep -oE -- '--[A-Za-z0-9-]+'); do
    if "$@" "$shown" --help >/dev/null 2>&1; then
      echo "FAIL: $name --help shows the value of $shown as required, and $shown without one is accepted" >&2
      failed=1
    fi
  done
  local option
  for option in $(grep -oE -- '(^|[ ,])--?[A-Za-z][A-Za-z0-9-]*' <<<"$help" | sed 's/^[ ,]*//' | sort -u); do
    [ "$option" = "-h" ] || [ "$option" = "--help" ] && continue
    checked=$((checked + 1))
    if ! grep -qE -- "(^|[^A-Za-z0-9-])${option}([^A-Za-z0-9-]|\$)" "$manual" "$manual_dir/README.md"; then
      echo "FAIL: $name $option is in --help but not in $manual or $manual_dir/README.md" >&2
      failed=1
    fi
  done
}
for tool in "$@"; do
  name=$(basename "$tool")
  manual=$manual_dir/$name.md
  [ -f "$manual" ] || { echo "FAIL: $name has no manual $manual" >&2; failed=1; continue; }
  check_help "$name" "$("$tool" --help)" "$manual" "$tool"
  if [ "$name" = bodysim ]; then
    for sub in $("$tool" --help | awk '/^Subcommands:/ {on = 1; next} on && !NF {exit} on {print $1}'); do
      check_help "$name $sub" "$("$tool" "$sub" --help)" "$manual" "$tool" "$sub"
    done
  fi
done
if [ "$checked" -lt 50 ]; then
  echo "FAIL: only $checked options found in the tools' --help (is the parsing broken?)" >&2
  failed=1
fi
[ "$failed" -eq 0 ] && echo "ok: $checked options of $# tools are in their manuals in $manual_dir"
exit "$failed"
