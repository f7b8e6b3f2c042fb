#!/usr/bin/env python3
"""Runs `bodysim check --balance-inertia` on every corpus model whose root joint is free
(as bodyinfo --format yaml reports it) and prints one Markdown row per model: checks passed,
the failing checks, and the wall time. Usage: corpus_checks.py BODYSIM BODYINFO CORPUS_DIR"""
import pathlib
import subprocess
import sys
import time


def root_is_free(bodyinfo, path):
    r = subprocess.run([bodyinfo, "--format", "yaml", "--no-config", str(path)], capture_output=True, text=True)
    if r.returncode == 2:
        return None
    for line in r.stdout.splitlines():
        s = line.strip()
        if s.startswith("joint_type:"):
            return s.split(":", 1)[1].strip() == "free"  # the first link is the root
    return False


def main():
    bodysim, bodyinfo, corpus = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
    print("| model | result | failing checks | wall s |")
    print("|---|---|---|---|")
    for path in sorted(corpus.rglob("*.body")):
        free = root_is_free(bodyinfo, path)
        if not free:
            continue
        start = time.monotonic()
        try:
            r = subprocess.run([bodysim, "check", "--balance-inertia", "--no-config", "-q", str(path)],
                               capture_output=True, text=True, timeout=600)
            out, code = r.stdout, r.returncode
        except subprocess.TimeoutExpired:
            out, code = "", "timeout"
        wall = time.monotonic() - start
        summary = next((l for l in out.splitlines() if l.endswith("checks passed")), "")
        failing = [l.split("  ")[1].strip() for l in out.splitlines() if l.startswith("FAIL")]
        if not summary:
            err = r.stderr.strip().splitlines()[-1] if code != "timeout" and r.stderr.strip() else str(code)
            summary = f"exit {code}: {err}"
        print(f"| {path.relative_to(corpus)} | {summary} | {'; '.join(failing)} | {wall:.1f} |", flush=True)


if __name__ == "__main__":
    main()
