#!/usr/bin/env python3
"""Every text output parses, whatever a name holds (issue 26, item 8).

    text_outputs.py BIN_DIR

Writes models whose model and link names hold one awkward character each (C0 and C1 controls,
DEL, line and paragraph separators, the byte order mark, non-characters, XML and YAML
metacharacters, a character outside the BMP) and runs every text output on them:
bodyinfo --format yaml (PyYAML must read it, and each name must come back exactly as PyYAML
reads it from the model), bodycheck --format json and sarif (Python's json; a finding's message
holds the exact name), bodycheck's GCC-style text (one line per diagnostic, no line break or
terminal control inside one, as many error lines as JSON errors), body2urdf and body2mjcf (expat;
or a refusal that writes nothing) and body2gltf's .gltf (json).
"""
import json
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ElementTree

import yaml

# YAML double-quoted escapes, so that the model file itself is plain ASCII.
AWKWARD = [r"\x01", r"\x1b[31m", r"\x7f", r"\x85", r"\x9b", r"\n", r"\r", r"\t", r"\u2028", r"\u2029",
           r"\uFEFF", r"\uFFFE", r"\uFFFF", r"\uFDD0", r"\U0001F916", r"\"", r"\\", "<&>", "]]>", "--", "'",
           ": #", "- ", "&a *b !t", "%", "@`"]

MODEL = """format: ChoreonoidBody
format_version: 2.0
name: "robot{c}"
links:
  - {{name: "base{c}", joint_type: free, mass: 1, inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1]}}
  - {{name: "arm{c}", parent: "base{c}", joint_type: revolute, joint_axis: Z, joint_id: 0, mass: {mass},
     inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1],
     elements: [{{type: Shape, geometry: {{type: Box, size: [0.1, 0.1, 0.1]}}}}]}}
"""

DIAGNOSTIC = re.compile(r"^\S.*:\d+:\d+: (error|warning|note|fatal error): .*$")
FOLDED = re.compile(r"^\S.*: note: \d+ more \[[a-z0-9-]+\] in this file, at lines? [0-9, ]+$")
LINE_BREAKING = re.compile("[\x00-\x08\x0a-\x1f\x7f\x80-\x9f\u2028\u2029]")


def run(args, cwd):
    return subprocess.run(args, cwd=cwd, capture_output=True, timeout=120)


def check_model(bin_dir, work, index, awkward):
    failures = []
    name = f"m{index}"
    path = os.path.join(work, name + ".body")
    with open(path, "w", encoding="ascii") as f:
        f.write(MODEL.format(c=awkward, mass=-1))  # a finding that names the link
    clean = os.path.join(work, name + "_clean.body")
    with open(clean, "w", encoding="ascii") as f:
        f.write(MODEL.format(c=awkward, mass=1))
    with open(path, encoding="utf-8") as f:
        reference = yaml.safe_load(f)  # PyYAML's reading of the names: the independent reference
    names = [link["name"] for link in reference["links"]]
    tool = lambda t: os.path.join(bin_dir, t)

    def fail(what):
        failures.append(f"{awkward!r}: {what}")

    r = run([tool("bodyinfo"), "--format", "yaml", path], work)
    try:
        info = yaml.safe_load(r.stdout.decode("utf-8"))
        if info.get("model_name") != reference["name"]:
            fail(f"bodyinfo yaml model_name {info.get('model_name')!r} != {reference['name']!r}")
        if [l["name"] for l in info.get("links", [])] != names:
            fail(f"bodyinfo yaml link names {[l['name'] for l in info.get('links', [])]!r} != {names!r}")
    except Exception as e:  # noqa: BLE001 - any failure to parse is the finding
        fail(f"bodyinfo --format yaml does not parse: {e}")

    documents = {}
    for fmt in ("json", "sarif"):
        r = run([tool("bodycheck"), "--format", fmt, path], work)
        try:
            documents[fmt] = json.loads(r.stdout.decode("utf-8"))
        except Exception as e:  # noqa: BLE001
            fail(f"bodycheck --format {fmt} does not parse: {e}")
    if "json" in documents:
        messages = [d["message"] for d in documents["json"]["diagnostics"]]
        if not any(names[1] in m for m in messages):
            fail(f"no bodycheck JSON message holds the name {names[1]!r}: {messages!r}")
    if "sarif" in documents:
        results = documents["sarif"]["runs"][0]["results"]
        if not any(names[1] in res["message"]["text"] for res in results):
            fail(f"no SARIF result holds the name {names[1]!r}")

    r = run([tool("bodycheck"), path], work)
    text = r.stdout.decode("utf-8")
    errors = 0
    # A diagnostic line, then its source line (the model's own text) and a caret line.
    lines = text.split("\n")[:-1]
    i = 0
    while i < len(lines):
        line = lines[i]
        if LINE_BREAKING.search(line):
            fail(f"bodycheck text line holds a control character: {line!r}")
        match = DIAGNOSTIC.match(line)
        if match:
            errors += match.group(1) == "error"
            if i + 2 < len(lines) and re.match(r"^ *\^$", lines[i + 2]):
                i += 2
        elif FOLDED.match(line):
            # A rule's repeats folded into one line (with its wrapped continuation lines).
            while i + 1 < len(lines) and re.match(r"^   [0-9, ]+$", lines[i + 1]):
                i += 1
        elif not line.startswith("bodycheck: "):  # the summary lines
            fail(f"bodycheck text line is neither a diagnostic, its source and caret nor the summary: {line!r}")
        i += 1
    if "json" in documents:
        expected = sum(d["severity"] == "error" for d in documents["json"]["diagnostics"])
        if errors != expected:
            fail(f"bodycheck text has {errors} error lines, JSON {expected} errors")

    for exporter, out in (("body2urdf", name + ".urdf"), ("body2mjcf", name + ".xml"), ("body2gltf", name + ".gltf")):
        target = os.path.join(work, out)
        r = run([tool(exporter), clean, "-o", target], work)
        if r.returncode == 2:
            if os.path.exists(target):
                fail(f"{exporter} exited 2 but wrote {out}")
            if b"[export-" not in r.stderr:
                fail(f"{exporter} exited 2 without a located export diagnostic: {r.stderr[-500:]!r}")
            continue
        if r.returncode not in (0, 1):
            fail(f"{exporter} exit {r.returncode}")
            continue
        try:
            if exporter == "body2gltf":
                with open(target, encoding="utf-8") as f:
                    json.load(f)
            else:
                ElementTree.parse(target)
        except Exception as e:  # noqa: BLE001
            fail(f"{exporter}'s {out} does not parse: {e}")
    return failures


def main():
    bin_dir = sys.argv[1]
    failures = []
    with tempfile.TemporaryDirectory() as work:
        for i, awkward in enumerate(AWKWARD):
            failures += check_model(bin_dir, work, i, awkward)
    for f in failures:
        print(f)
    print(f"{len(AWKWARD)} names, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
