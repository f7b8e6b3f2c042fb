#!/usr/bin/env python3
"""An export that changes a value says so, at the value, as bodycheck judges it (issue 44).

    changed_values.py TOOL=PATH... --cases DIR
    changed_values.py TOOL=PATH... --silent MODEL_OR_DIR...

TOOL is body2urdf, body2mjcf and bodycheck, and body2gltf where it is given.

--cases: each mutant in DIR (tests/data/export_changed) carries one value an export cannot
write as given, on a line marked `# <- changed`. The table below says, per tool and option set,
which rule must be reported at that line and at the column of its key (counted here from the
text, not taken from the tools), with which severity, which exit code, and whether the output
is written (then, URDF and MJCF, with the change commented in it). bodycheck must report its rule at the same
line and column: one gate, one place.

--silent: every .body model under the given files and folders is exported by body2urdf,
body2mjcf (as given, and also with --actuators velocity) and body2gltf; none may report a changed
value (export-value-changed) or an asymmetric inertia, except the findings listed in SILENT_EXPECTED
with their reason.
"""
import os
import re
import subprocess
import sys
import tempfile

LINE = re.compile(r"^(?P<file>.+?):(?P<line>\d+):(?P<column>\d+): (?P<severity>fatal|error|warning|note): "
                  r"(?P<message>.*) \[(?P<rule>[a-z0-9-]+)\]$")
CHANGED_RULES = {"export-value-changed", "inertia-asymmetric"}

# file -> (key on the marked line, bodycheck's rule and severity, runs); the key is "KEY" for a
# finding at KEY's value, "node:KEY" for one at the mapping that starts with KEY (a RigidBody).
# run: (tool, options, rule, severity, exit code, written)
CASES = {
    "asymmetric_inertia.body": ("inertia", ("inertia-asymmetric", "error"), [
        ("body2urdf", [], "inertia-asymmetric", "error", 2, False),
        ("body2mjcf", [], "inertia-asymmetric", "error", 2, False),
        ("body2urdf", ["--balance-inertia"], "export-value-changed", "warning", 1, True),
        ("body2mjcf", ["--balance-inertia"], "export-value-changed", "warning", 1, True),
        ("body2urdf", ["--balance-inertia", "--strict"], "export-value-changed", "error", 2, False),
        ("body2mjcf", ["--balance-inertia", "--strict"], "export-value-changed", "error", 2, False),
    ]),
    "asymmetric_rigid_body.body": ("node:type", ("inertia-asymmetric", "error"), [
        ("body2urdf", [], "inertia-asymmetric", "error", 2, False),
        ("body2mjcf", [], "inertia-asymmetric", "error", 2, False),
        ("body2urdf", ["--balance-inertia"], "export-value-changed", "warning", 1, True),
        ("body2mjcf", ["--balance-inertia"], "export-value-changed", "warning", 1, True),
    ]),
    "axis_not_unit.body": ("joint_axis", ("joint-axis-not-unit", "warning"), [
        ("body2urdf", [], "export-value-changed", "warning", 1, True),
        ("body2mjcf", [], "export-value-changed", "warning", 1, True),
        ("body2gltf", [], "export-value-changed", "warning", 1, True),
        ("body2urdf", ["--strict"], "export-value-changed", "error", 2, False),
        ("body2mjcf", ["--strict"], "export-value-changed", "error", 2, False),
        ("body2gltf", ["--strict"], "export-value-changed", "error", 2, False),
    ]),
    "prismatic_axis_not_unit.body": ("joint_axis", ("joint-axis-not-unit", "warning"), [
        ("body2urdf", [], "export-value-changed", "warning", 1, True),
        ("body2mjcf", [], "export-value-changed", "warning", 1, True),
        ("body2mjcf", ["--strict"], "export-value-changed", "error", 2, False),
    ]),
    # URDF writes the track's axis only in a comment, as given: nothing changed there.
    "track_axis_not_unit.body": ("joint_axis", ("joint-axis-not-unit", "warning"), [
        ("body2mjcf", [], "export-value-changed", "warning", 1, True),
        ("body2gltf", [], "export-value-changed", "warning", 1, True),
        ("body2mjcf", ["--strict", "--allow-loss", "tracks"], "export-value-changed", "error", 2, False),
    ]),
    # URDF holds a zero-width range as written.
    "zero_width_range.body": ("joint_range", ("joint-range-zero-width", "warning"), [
        ("body2mjcf", [], "export-value-changed", "warning", 1, True),
        ("body2mjcf", ["--strict"], "export-value-changed", "error", 2, False),
    ]),
    # Only an actuator writes the velocity range as a range (URDF's bound 0 holds it).
    "zero_velocity_range.body": ("joint_velocity_range", None, [
        ("body2mjcf", ["--actuators", "velocity"], "export-value-changed", "warning", 1, True),
        ("body2mjcf", ["--actuators", "velocity", "--strict"], "export-value-changed", "error", 2, False),
    ]),
}

# Findings of a changed value on valid models, each with why it is right: (model path relative to
# the folder given, tool, rule, line) -> reason.
SILENT_EXPECTED = {}


def findings(text, model):
    out = []
    for line in text.splitlines():
        m = LINE.match(line)
        if m and os.path.exists(m["file"]) and os.path.samefile(m["file"], model):
            out.append((m["rule"], int(m["line"]), int(m["column"]), m["severity"], m["message"]))
    return out


def export(tools, tool, model, options, out_dir):
    extension = {"body2urdf": "urdf", "body2mjcf": "xml", "body2gltf": "glb"}[tool]
    target = os.path.join(out_dir, f"{tool}.{extension}")
    if os.path.exists(target):
        os.remove(target)
    proc = subprocess.run([tools[tool], "--no-config", model, "-o", target] + options, capture_output=True,
                          text=True, timeout=600)
    written = None
    if os.path.exists(target):
        with open(target, "rb") as f:
            written = f.read().decode("utf-8", errors="replace")
    return proc, written


def key_place(model, key):
    with open(model, encoding="utf-8") as f:
        lines = f.read().splitlines()
    marked = [i for i, text in enumerate(lines) if text.rstrip().endswith("# <- changed")]
    if len(marked) != 1:
        raise RuntimeError(f"{model}: needs exactly one '# <- changed' line")
    # "KEY": the finding points at KEY's value; "node:KEY": at the mapping that starts with KEY.
    node = key.startswith("node:")
    key = key[len("node:"):] if node else key
    text = lines[marked[0]]
    column = text.find(key + ":")
    if column < 0:
        raise RuntimeError(f"{model}: the marked line has no key '{key}'")
    if not node:
        column += len(key) + 1
        column += len(text[column:]) - len(text[column:].lstrip(" "))
    return marked[0] + 1, column + 1


def check_cases(tools, folder):
    failures = []
    for name, (key, bodycheck_rule, runs) in sorted(CASES.items()):
        model = os.path.join(folder, name)
        line, column = key_place(model, key)
        before = len(failures)
        if bodycheck_rule and "bodycheck" in tools:
            proc = subprocess.run([tools["bodycheck"], "--no-config", model], capture_output=True, text=True,
                                  timeout=300)
            found = findings(proc.stdout + proc.stderr, model)
            if not any(f[:4] == (bodycheck_rule[0], line, column, bodycheck_rule[1]) for f in found):
                failures.append(f"{name}: bodycheck does not report {bodycheck_rule[1]} [{bodycheck_rule[0]}] at "
                                f"{line}:{column} (found {[f[:4] for f in found]})")
        with tempfile.TemporaryDirectory() as out:
            for tool, options, rule, severity, code, written in runs:
                if tool not in tools:
                    continue
                what = f"{name}: {tool} {' '.join(options)}".rstrip()
                proc, text = export(tools, tool, model, options, out)
                found = findings(proc.stdout + proc.stderr, model)
                if not any(f[:4] == (rule, line, column, severity) for f in found):
                    failures.append(f"{what}: no {severity} [{rule}] at {line}:{column} (found "
                                    f"{[f[:4] for f in found]})")
                if proc.returncode != code:
                    failures.append(f"{what}: exit {proc.returncode}, expected {code}")
                if written and text is None:
                    failures.append(f"{what}: not written")
                elif written and tool != "body2gltf" and "<!-- export-value-changed: " not in text:
                    failures.append(f"{what}: written without the change commented in it")
                if not written and text is not None:
                    failures.append(f"{what}: written, but it must not be")
        print(f"{name}: {len(runs)} runs at {line}:{column}; {len(failures) - before} failures")
    return failures


def models_under(paths):
    for path in paths:
        if os.path.isdir(path):
            for root, _, files in os.walk(path):
                for f in sorted(files):
                    if f.endswith(".body"):
                        yield path, os.path.join(root, f)
        else:
            yield os.path.dirname(path), path


def check_silent(tools, paths):
    failures = []
    count = 0
    seen = set()
    with tempfile.TemporaryDirectory() as out:
        for base, model in models_under(paths):
            count += 1
            rel = os.path.relpath(model, base)
            for tool, options in (("body2urdf", []), ("body2mjcf", []), ("body2mjcf", ["--actuators", "velocity"]),
                                  ("body2gltf", [])):
                if tool not in tools:
                    continue
                proc, _ = export(tools, tool, model, options, out)
                if proc.returncode not in (0, 1, 2):
                    failures.append(f"{rel}: {tool} exited {proc.returncode}")
                for rule, line, column, severity, message in findings(proc.stdout + proc.stderr, model):
                    if rule not in CHANGED_RULES:
                        continue
                    key = (rel, tool, rule, line)
                    if key in SILENT_EXPECTED:
                        seen.add(key)
                        continue
                    failures.append(f"{rel}:{line}:{column}: {tool} {' '.join(options)}: {severity}: {message} "
                                    f"[{rule}]")
    for key in sorted(set(SILENT_EXPECTED) - seen):
        failures.append(f"expected, not reported (update SILENT_EXPECTED): {key}")
    print(f"{count} valid models exported; {len(seen)} expected findings; {len(failures)} failures")
    return failures


def main():
    args = sys.argv[1:]
    tools = dict(arg.split("=", 1) for arg in args if "=" in arg)
    rest = [arg for arg in args if "=" not in arg]
    if not {"body2urdf", "body2mjcf"} <= set(tools) or len(rest) < 2 or rest[0] not in ("--cases", "--silent"):
        print(__doc__)
        return 2
    failures = check_cases(tools, rest[1]) if rest[0] == "--cases" else check_silent(tools, rest[1:])
    for f in failures:
        print("FAIL " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
