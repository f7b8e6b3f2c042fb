#!/usr/bin/env python3
"""One defect, one place: bodycheck, body2mjcf, body2urdf and bodysim on the same defective files.

    same_location.py TOOL=PATH... CASE.body...

TOOL is bodycheck, body2mjcf, body2urdf or bodysim (left out where it is not built).

Each case (tests/data/physical) is valid (`# defect: none`: no tool may report a finding of
the gate) or carries one defect of the physical-validity gate
(bodyfmt/physical.h), written on a line of its own and marked there with `# <- defect`. Its
header names what each tool must report for it:

    # defect: inertia-nonpositive-mass@bodycheck export-value-changed@body2mjcf

Every tool is run on the file (bodycheck's JSON report, the others' `file:line:col: ...
[rule]` lines). The test fails when a named tool does not report its rule at the marked line,
and when two tools report the same rule at different places (line and column), whether the
file names the rule or not. A tool the case does not name (bodysim for a joint axis, which it
does not check today) is still compared for every rule it shares with another tool.
"""
import json
import os
import re
import subprocess
import sys
import tempfile

TOOLS = ["bodycheck", "body2mjcf", "body2urdf", "bodysim"]
# The gate's rules, and the tools' own rules for what they do about its findings.
GATE_RULES = {"inertia-asymmetric", "inertia-nonpositive-mass", "inertia-not-positive-definite", "inertia-triangle",
              "inertia-tiny", "joint-axis-zero", "joint-axis-not-unit", "joint-range-reversed",
              "joint-range-zero-width", "export-value-changed", "export-range-reversed", "dynamics-inertia-balanced"}
LINE = re.compile(r"^(?P<file>.+?):(?P<line>\d+):(?P<column>\d+): (?:fatal|error|warning|note): .*\[(?P<rule>[a-z0-9-]+)\]$")


def run(exe, tool, model, out):
    if tool == "bodycheck":
        args = [exe, "--format", "json", "--no-config", model]
    elif tool == "bodysim":
        args = [exe, "check", "--no-config", model]
    else:
        extension = tool[len("body2"):]
        args = [exe, "--no-config", model, "-o", os.path.join(out, f"{tool}.{extension}")]
    proc = subprocess.run(args, capture_output=True, text=True, timeout=300)
    if proc.returncode not in (0, 1, 2):
        raise RuntimeError(f"{tool} exited {proc.returncode} on {model}\n{proc.stderr[-2000:]}")
    found = set()
    if tool == "bodycheck":
        for d in json.loads(proc.stdout)["diagnostics"]:
            if os.path.samefile(d["file"], model):
                found.add((d["rule"], d["line"], d["column"]))
    else:
        for text in (proc.stdout + proc.stderr).splitlines():
            m = LINE.match(text)
            if m and os.path.exists(m["file"]) and os.path.samefile(m["file"], model):
                found.add((m["rule"], int(m["line"]), int(m["column"])))
    return found


def check_case(tools, model):
    with open(model, encoding="utf-8") as f:
        lines = f.read().splitlines()
    marked = [i + 1 for i, text in enumerate(lines) if text.rstrip().endswith("# <- defect")]
    header = [text for text in lines if text.startswith("# defect:")]
    failures = []
    name = os.path.basename(model)
    valid = header == ["# defect: none"]
    if len(header) != 1 or len(marked) != (0 if valid else 1):
        return [f"{name}: needs one '# defect:' header, and one '# <- defect' line unless it is 'none'"]
    with tempfile.TemporaryDirectory() as out:
        findings = {tool: run(exe, tool, model, out) for tool, exe in tools.items()}
    if valid:
        # A valid variant: no tool reports anything of the gate.
        for tool, found in findings.items():
            wrong = sorted(f for f in found if f[0] in GATE_RULES)
            if wrong:
                failures.append(f"{name}: valid, but {tool} reports {wrong}")
        print(f"{name}: valid; {len(failures)} failures")
        return failures
    defect_line = marked[0]
    expected = [item.split("@") for item in header[0].split(":", 1)[1].split()]
    # Each named tool reports its rule at the marked line.
    for rule, tool in expected:
        if tool not in findings:
            continue
        at = sorted((line, column) for r, line, column in findings[tool] if r == rule)
        if not any(line == defect_line for line, _ in at):
            failures.append(f"{name}: {tool} does not report [{rule}] at line {defect_line} (found at {at})")
    # The named findings of one defect share one location across tools, whatever their rules.
    places = {}
    for rule, tool in expected:
        if tool in findings:
            for r, line, column in findings[tool]:
                if r == rule and line == defect_line:
                    places.setdefault((line, column), []).append(f"{tool} [{rule}]")
    if len(places) > 1:
        failures.append(f"{name}: one defect at different columns: {places}")
    # Every rule that two tools report is reported at the same places by both.
    by_rule = {}
    for tool, found in findings.items():
        for rule, line, column in found:
            by_rule.setdefault(rule, {}).setdefault(tool, set()).add((line, column))
    for rule, per_tool in sorted(by_rule.items()):
        if len(per_tool) > 1 and len({frozenset(v) for v in per_tool.values()}) > 1:
            failures.append(f"{name}: [{rule}] located differently: {dict(sorted(per_tool.items()))}")
    compared = sum(1 for per_tool in by_rule.values() if len(per_tool) > 1)
    print(f"{name}: defect at line {defect_line}; {compared} rules shared between tools; "
          f"{len(failures)} failures")
    return failures


def main():
    tools = dict(arg.split("=", 1) for arg in sys.argv[1:] if "=" in arg)
    cases = [arg for arg in sys.argv[1:] if "=" not in arg]
    unknown = set(tools) - set(TOOLS)
    if unknown or not {"bodycheck", "body2mjcf"} <= set(tools):
        print(f"usage: same_location.py TOOL=PATH... CASE.body... (tools: {', '.join(TOOLS)})")
        return 2
    for tool in TOOLS:
        if tool not in tools:
            print(f"note: {tool} is not built; its findings are not compared")
    failures = []
    for model in cases:
        failures += check_case(tools, model)
    for f in failures:
        print("FAIL " + f)
    print(f"{len(cases)} cases, {len(tools)} tools, {len(failures)} failures")
    return 1 if failures or not cases else 0


if __name__ == "__main__":
    sys.exit(main())
