#!/usr/bin/env python3
"""bodyview prints one summary line of its findings (the page lists them); --verbose prints them all.

usage: summary_test.py BODYVIEW BODYCHECK OUT_DIR MODEL...

For each MODEL, the expected findings are bodycheck's (`--format json`, the same loader and rules),
not bodyview's own:
- without --verbose, a written page gets exactly one `bodyview: ... findings ...` line whose counts
  by severity are bodycheck's (notes left out under -q, as -q leaves them out everywhere), and no
  located diagnostic; a model without findings gets no summary line;
- with --verbose, one located diagnostic (`file:line:col: severity: ... [rule]`) for each of
  bodycheck's findings, and no summary line;
- a model that cannot be loaded writes no page, so its located error is printed in full anyway.
"""
import json
import os
import pathlib
import re
import subprocess
import sys

LOCATED = re.compile(r"^(.+?):(\d+):(\d+): (note|warning|error|fatal error): .*\[([a-z0-9-]+)\]$")
COUNT = re.compile(r"(\d+) (fatal|error|warning|note)s?\b")


def bodycheck_findings(bodycheck, model):
    out = subprocess.run([bodycheck, "--format", "json", model], capture_output=True, text=True).stdout
    return json.loads(out)["diagnostics"]


def findings_of(stderr):
    """(file, line, column, severity, rule) of each located diagnostic printed."""
    found = []
    for line in stderr.splitlines():
        m = LOCATED.match(line)
        if m:
            severity = "fatal" if m[4] == "fatal error" else m[4]
            found.append((os.path.realpath(m[1]), int(m[2]), int(m[3]), severity, m[5]))
    return sorted(found)


def bodycheck_counts(bodycheck, model, quiet):
    counts = {}
    for d in bodycheck_findings(bodycheck, model):
        if quiet and d["severity"] == "note":
            continue
        counts[d["severity"]] = counts.get(d["severity"], 0) + 1
    return counts


def summary_lines(stderr):
    return [l for l in stderr.splitlines() if l.startswith("bodyview: ") and "finding" in l]


def main():
    bodyview, bodycheck, out = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
    models = sys.argv[4:]
    out.mkdir(parents=True, exist_ok=True)
    failures = []
    summarised = 0
    for model in models:
        name = pathlib.Path(model).stem
        page = out / f"{name}.html"
        for quiet in (False, True):
            flags = ["-q"] if quiet else []
            expected = bodycheck_counts(bodycheck, model, quiet)
            run = subprocess.run([bodyview, model, *flags, "-o", str(page)], capture_output=True, text=True)
            if run.returncode == 2:
                failures.append(f"{name}: bodyview exit 2: {run.stderr[-400:]}")
                continue
            lines = summary_lines(run.stderr)
            if findings_of(run.stderr):
                failures.append(f"{name} {flags}: located diagnostics without --verbose:\n{run.stderr[-600:]}")
            if not expected:
                if lines:
                    failures.append(f"{name} {flags}: a summary line for a model without findings: {lines}")
                continue
            if len(lines) != 1:
                failures.append(f"{name} {flags}: {len(lines)} summary lines, 1 expected:\n{run.stderr[-600:]}")
                continue
            got = {kind: int(n) for n, kind in COUNT.findall(lines[0])}
            if got != expected:
                failures.append(f"{name} {flags}: summary {lines[0]!r} counts {got}, bodycheck {expected}")
            if str(page) not in lines[0]:
                failures.append(f"{name} {flags}: the summary does not say where the findings are: {lines[0]!r}")
            summarised += 1
        verbose = subprocess.run([bodyview, model, "--verbose", "-o", str(page)], capture_output=True, text=True)
        expected = sorted((os.path.realpath(d["file"]), d["line"], d["column"], d["severity"], d["rule"])
                          for d in bodycheck_findings(bodycheck, model))
        if findings_of(verbose.stderr) != expected:
            failures.append(f"{name} --verbose: {len(findings_of(verbose.stderr))} located diagnostics, bodycheck "
                            f"finds {len(expected)}:\n{verbose.stderr[-600:]}")
        if summary_lines(verbose.stderr):
            failures.append(f"{name} --verbose: a summary line: {summary_lines(verbose.stderr)}")

    # No page, nothing to look at: the error is printed where the user is.
    broken = out / "broken.body"
    broken.write_text("format: ChoreonoidBody\nformat_version: 2.0\nname: Broken\nlinks: [\n")
    run = subprocess.run([bodyview, str(broken), "-o", str(out / "broken.html")], capture_output=True, text=True)
    if run.returncode != 2 or not findings_of(run.stderr):
        failures.append(f"a model that cannot be loaded: exit {run.returncode}, no located error:\n{run.stderr[-600:]}")
    if summarised == 0:
        failures.append("no model had findings to summarise: the test checks nothing")
    for f in failures:
        print("FAIL: " + f)
    print(f"summary: {len(models)} models, {summarised} summaries, " + ("FAIL" if failures else "OK"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
