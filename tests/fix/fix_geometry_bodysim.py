#!/usr/bin/env python3
"""`bodysim check` simulates the corpus models `bodycheck --fix=geometry` fixed (issue 39).

usage: fix_geometry_bodysim.py BODYCHECK BODYSIM CORPUS_DIR WORK_DIR

In a fresh writable copy of the corpus, each model is fixed in one command (`bodycheck
--fix=geometry --fix-includes`) and `bodysim check` (no --balance-inertia) runs on the fixed
file: it must exit 0, every check passed or skipped, free roots and fixed roots alike (a fixed
root gets the checks that apply to it: mass matrix, zero-g, joint ranges, gravity load, belt
speed, determinism). Where the fix has no tensor to write (fix-geometry-unavailable: a RigidBody
element or link with no solid shape to compute it from), bodysim must still refuse the model for
its written tensor, naming the rule at its line; those models are listed in UNAVAILABLE. A model in
KNOWN_FAILURES may fail only the checks listed there (false alarms of the kind issue 36
describes); one in KNOWN_STIFF_CONTACT must stop at bodysim's step budget on the floor contact of
the link named there (issue 36: a stiff contact is not found before the run), whatever the fix
did. A listed model that does better fails the test too, so the lists cannot go stale.

CI runs SAMPLE (about 8 s): models whose written tensor bodysim refuses (two tanks, ellipsoid1,
crawler) and a fixed root whose implausible tensors bodysim accepts and the fix replaces (UR5). BODYFMT_FULL_CORPUS=1 runs every corpus model (about 8 minutes on one core). The
corpus itself is only read.
"""
import os
import pathlib
import re
import subprocess
import sys
import time

from fix_geometry import writable_copy  # the same writable corpus copy as fix.geometry

SAMPLE = ["Tank/SimpleTank.body", "Tank/Tank.body", "misc/ellipsoid1.body", "misc/crawler.body",
          "UniversalRobots/UR5.body"]

# model -> the rule bodysim refuses it with: the fix has no shape to compute its tensor from. The
# crawler, whose body's tensor a RigidBody carries, was here until the fix recomputed RigidBody
# elements from the shapes below them (issue 47).
UNAVAILABLE = {}

# model -> {failing check (its text in bodysim's report): reason}; issue 36's false alarms.
KNOWN_FAILURES = {}

# model -> the link whose floor contact stops the integrator (bodysim's step budget: issue 36's
# "a stiff contact is found before the run"), before the fix and after it; the run must stop there
# and nowhere else.
KNOWN_STIFF_CONTACT = {
    # 126 points of 6.7e5 N/m on a 0.17 kg link: 3.3e5 rad/s; the fix changes WAIST only.
    "misc/ClosedLinkSample.body": "J1",
    # Before: the Coupler (written 1e-6 kg·m², 62 times below its shape's); UR5-2F85.body's fix
    # replaces it in the included gripper, and then 2.27e4 N/m on the 0.0273 kg finger stops it.
    "Robotiq/2F-85.body": "Finger1_finger",
}


def run(*args, cwd=None, timeout=900):
    return subprocess.run(list(args), capture_output=True, text=True, cwd=cwd, timeout=timeout)


def main():
    bodycheck, bodysim, corpus, work = sys.argv[1:5]
    full = os.environ.get("BODYFMT_FULL_CORPUS") == "1"
    copy = os.path.join(work, "corpus")
    writable_copy(corpus, copy)
    models = (sorted(str(p.relative_to(copy)) for p in pathlib.Path(copy).rglob("*.body")) if full else SAMPLE)
    failures, rows = [], []
    refused_before = 0
    # Every model fixed first, so that a model sees its includes fixed whatever the order (the
    # tanks share TankBody.body; UR5-2F85.body fixes the Robotiq gripper it includes).
    fixed = []
    for model in models:
        if not os.path.exists(os.path.join(copy, model)):
            failures.append(f"{model}: not in the corpus")
            continue
        fix = run(bodycheck, "--no-config", "--fix=geometry", "--fix-includes", model, cwd=copy)
        if fix.returncode not in (0, 1):
            failures.append(f"{model}: --fix=geometry exit {fix.returncode}: {fix.stderr[-400:]}")
            continue
        fixed.append(model)
    for model in fixed:
        before = run(bodysim, "check", "--no-config", "-q", model, cwd=corpus)  # the corpus is only read
        refused_before += before.returncode == 2
        start = time.monotonic()
        sim = run(bodysim, "check", "--no-config", "-q", model, cwd=copy)
        wall = time.monotonic() - start
        out = sim.stdout + sim.stderr
        failed = [m.group(1).strip() for m in re.finditer(r"^FAIL  (.*)$", sim.stdout, re.M)]
        summary = next((l for l in sim.stdout.splitlines() if "checks passed" in l), f"exit {sim.returncode}")
        rows.append(f"{model:36} before: exit {before.returncode}  fixed: exit {sim.returncode}  {summary}  {wall:.1f} s")
        if model in UNAVAILABLE:
            rule = UNAVAILABLE[model]
            if sim.returncode != 2 or not re.search(rf"{re.escape(model)}:\d+:\d+: error: .*\[{rule}\]", out):
                failures.append(f"{model}: listed as refused for {rule} (no tensor the fix can replace), "
                                f"but bodysim exit {sim.returncode}: {out[-400:]}")
            continue
        if model in KNOWN_STIFF_CONTACT:
            link = KNOWN_STIFF_CONTACT[model]
            if sim.returncode != 2 or not re.search(r"fatal error: the integrator needed more than \d+ steps per simulated "
                                                    rf"second.*the floor contact of link \"{re.escape(link)}\"", out):
                failures.append(f"{model}: listed as stopped by the stiff floor contact of {link} (issue 36), "
                                f"but exit {sim.returncode}: {out[-400:]}")
            continue
        if sim.returncode == 2 or re.search(r"fatal error", out):
            failures.append(f"{model}: the fixed model is not simulated (exit {sim.returncode}): {out[-600:]}")
            continue
        known = KNOWN_FAILURES.get(model, {})
        unexpected = [f for f in failed if not any(f.startswith(k) for k in known)]
        stale = [k for k in known if not any(f.startswith(k) for f in failed)]
        if unexpected:
            failures.append(f"{model}: fixed, bodysim check fails {unexpected}")
        if stale:
            failures.append(f"{model}: listed as failing {stale} (issue 36), which now pass: update KNOWN_FAILURES")
        if sim.returncode not in (0, 1) or (sim.returncode == 1) != bool(failed):
            failures.append(f"{model}: exit {sim.returncode} with {len(failed)} failed checks")
    if refused_before == 0:
        failures.append("bodysim refused none of the models before the fix: the sample proves nothing")
    for r in rows:
        print(r)
    for f in failures:
        print("FAIL", f)
    print(f"{len(rows)} models ({'the whole corpus' if full else 'the CI sample; BODYFMT_FULL_CORPUS=1 for all'}), "
          f"{refused_before} refused by bodysim before the fix; {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
