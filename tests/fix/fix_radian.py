#!/usr/bin/env python3
"""`bodycheck --fix --upgrade` on tests/data/fix/radian_v1.body: the format 1.0 radian-mode model
with every angle-bearing key of body-format-spec §3.

usage: fix_radian.py BODYCHECK BODYINFO MODEL WORK_DIR

Checks, on a copy of MODEL:
  * the header becomes format_version 2.0 and angle_unit degree, and no load-legacy-key or
    load-format-upgrade finding is left;
  * line by line, the numbers are the original ones, except on lines marked `# deg X ...`:
    there each X (a radian value) is X * 180 / pi (within 1e-12 relative), computed here;
  * the copy loads to the same model as the original (bodyinfo --format yaml, 1e-12);
  * a second --fix --upgrade changes nothing.
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys

from fix_corpus import bodyinfo, same

NUMBER = re.compile(r"(?<![\w.])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?![\w.])")


def numbers(line):
    return [float(x) for x in NUMBER.findall(line.split("#")[0])]


def main():
    bodycheck, tool, model, work = sys.argv[1:5]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    copy = os.path.join(work, os.path.basename(model))
    shutil.copy(model, copy)
    run = subprocess.run([bodycheck, "--fix", "--upgrade", "-q", "--no-config", copy], capture_output=True,
                         text=True)
    failures = []
    if run.returncode not in (0, 1):
        failures.append(f"bodycheck --fix --upgrade exited {run.returncode}: {run.stderr}")
    with open(model) as f:
        before = f.read().split("\n")
    with open(copy) as f:
        after = f.read().split("\n")
    converted = 0
    if len(before) != len(after):
        failures.append(f"{len(after)} lines instead of {len(before)}")
    for number, (old, new) in enumerate(zip(before, after), start=1):
        marks = None if old.lstrip().startswith("#") else re.search(r"# deg ((?:\S+ ?)+)$", old)
        radians = [float(x) for x in marks.group(1).split()] if marks else []
        expected = [2.0] if old.startswith("formatVersion:") else numbers(old)
        for value in radians:  # each marked value, in order, becomes degrees
            expected[expected.index(value)] = math.degrees(value)
        got = numbers(new)
        if len(got) != len(expected) or any(
                abs(a - b) > 1e-12 * max(1.0, abs(a)) for a, b in zip(got, expected)):
            failures.append(f"line {number}: {new.strip()!r}, expected the numbers {expected}")
        converted += len(radians)
    text = "\n".join(after)
    if "format_version: 2.0" not in text or "angle_unit: degree" not in text:
        failures.append("the header is not format_version: 2.0 / angle_unit: degree")
    out = subprocess.run([bodycheck, "--format", "json", "--no-config", copy], capture_output=True, text=True)
    left = [d for d in json.loads(out.stdout)["diagnostics"] if d["rule"] in ("load-legacy-key", "load-format-upgrade")]
    for d in left:
        failures.append(f"left after the upgrade: {d['line']}:{d['column']}: {d['message']}")
    difference = same(bodyinfo(tool, model), bodyinfo(tool, copy))
    if difference:
        failures.append(f"the upgraded file loads a different model: {difference}")
    with open(copy, "rb") as f:
        first = f.read()
    subprocess.run([bodycheck, "--fix", "--upgrade", "-q", "--no-config", copy], capture_output=True)
    with open(copy, "rb") as f:
        if f.read() != first:
            failures.append("a second --fix --upgrade changed the file")
    print(f"{converted} radian values written in degrees")
    if converted < 40:
        failures.append(f"only {converted} marked values: the model lost its angle keys")
    for f in failures:
        print("FAIL", f)
    shutil.rmtree(work, ignore_errors=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
