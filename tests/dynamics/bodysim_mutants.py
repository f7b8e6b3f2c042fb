#!/usr/bin/env python3
"""bodysim's mutation score: each mutant is one physical change to one of our own example
models, with the outcome bodysim must give it:
    fail   exit 1, the cause named (every `cause` text in the output, on a FAIL line)
    pass   exit 0, no FAIL line (the `said` texts in the output, when given)
    skip   exit 0, the SKIP line(s) with their reasons (`said`)
    refuse exit 2, the finding at its line (`said`: "{line}" is the line of the edit)
A `said` text starting with "re:" is a regular expression.
A mutant is a list of exact text replacements; each must match the base model exactly once,
so that a mutant cannot silently be the base model.
    bodysim_mutants.py BODYSIM EXAMPLES_DIR DATA_DIR SHARED_DIR WORK_DIR [--with-mujoco]
Mutants run with `--cross-check mujoco` need a bodysim built with MuJoCo (--with-mujoco); without
it they are listed as not run, and the table says so.
Prints the table (mutant, expected, got) and exits 1 when any mutant gets another outcome.
"""
import os
import re
import subprocess
import sys

# base: (file under EXAMPLES_DIR or DATA_DIR, the bodysim subcommand and options)
BASES = {
    "scout": ("examples/scouttank.body", ["check-tank"]),
    "skid": ("data/bodysim/skidder.body", ["check-tank"]),
    "arm": ("examples/arm.body", ["check"]),
    "conveyor": ("shared/corpus/choreonoid/misc/conveyor.body", ["check"]),
}

# ScoutTank's track axes turned over, one edit each.
RIGHT_FLIPPED = ("    joint_axis: Y\n    mass: 3.0\n    inertia: [ 0.01, 0,      0,\n               0,    0.1664, 0,\n               0,    0,      0.1636 ]\n    elements: &belt",
                 "    joint_axis: -Y\n    mass: 3.0\n    inertia: [ 0.01, 0,      0,\n               0,    0.1664, 0,\n               0,    0,      0.1636 ]\n    elements: &belt")
LEFT_FLIPPED = ("    translation: [0, 0.31, 0]\n    joint_type: pseudo_continuous_track\n    joint_axis: Y",
                "    translation: [0, 0.31, 0]\n    joint_type: pseudo_continuous_track\n    joint_axis: -Y")

MUTANTS = [
    # --- tracked vehicles: defects that must fail with their cause named ----------------------
    ("scout", "right track axis flipped", [("    joint_axis: Y\n    mass: 3.0\n    inertia: [ 0.01, 0,      0,\n               0,    0.1664, 0,\n               0,    0,      0.1636 ]\n    elements: &belt", "    joint_axis: -Y\n    mass: 3.0\n    inertia: [ 0.01, 0,      0,\n               0,    0.1664, 0,\n               0,    0,      0.1636 ]\n    elements: &belt")],
     "fail", ["tracks drive against each other", "\"BELT_A\" (axis (0, -1, 0)", "\"BELT_B\" (axis (0, 1, 0)"]),
    ("skid", "left track axis flipped", [("  - name: TRACK_LEFT\n    parent: BODY\n    translation: [0.02, 0.27, -0.03]\n    joint_type: pseudo_continuous_track\n    joint_axis: -Y", "  - name: TRACK_LEFT\n    parent: BODY\n    translation: [0.02, 0.27, -0.03]\n    joint_type: pseudo_continuous_track\n    joint_axis: Y")],
     "fail", ["tracks drive against each other", "TRACK_LEFT", "TRACK_RIGHT"]),
    ("scout", "a track that does not touch the floor", [("translation: [0, -0.31, 0]", "translation: [0, -0.31, 0.05]")],
     "fail", ["track \"BELT_A\" does not reach the floor"]),
    ("scout", "hull hanging below the tracks", [("geometry: { type: Box, size: [0.7, 0.5, 0.14] }", "geometry: { type: Box, size: [0.7, 0.5, 0.4] }")],
     "fail", ["does not reach the floor", "link \"HULL\""]),
    ("scout", "centre of mass outside the support polygon", [("    mass: 20.0\n    center_of_mass: [0, 0, 0]", "    mass: 20.0\n    center_of_mass: [1.2, 0, 0]")],
     "fail", ["outside the support polygon", "the centre of mass projects to ("]),
    ("skid", "centre of mass outside the support polygon (to the side)", [("center_of_mass: [0.03, 0, 0.02]", "center_of_mass: [0.03, 0.9, 0.02]")],
     "fail", ["outside the support polygon"]),
    ("scout", "a link that is not a track", [("    translation: [0, -0.31, 0]\n    joint_type: pseudo_continuous_track", "    translation: [0, -0.31, 0]\n    joint_type: fixed")],
     "refuse", ["touching the floor but not a track: \"BELT_A\" (fixed joint)"]),
    ("scout", "a reversed joint range", [("joint_range: [-30, 5]", "joint_range: [5, -30]")],
     "refuse", ["scouttank.body:{line}:", "[joint-range-reversed]"]),
    ("scout", "a moving link with zero mass", [("    joint_axis: Z\n    joint_range: unlimited\n    mass: 6.0", "    joint_axis: Z\n    joint_range: unlimited\n    mass: 0.0")],
     "refuse", ["scouttank.body:{line}:", "[inertia-nonpositive-mass]"]),
    ("scout", "a turret servo too weak to hold the cannon (--p-gain 1)", [], "fail", ["FAIL  turret: pitch sag under gravity"], ["--p-gain", "1"]),
    # --- valid variants that must pass ---------------------------------------------------------------
    ("scout", "both tracks flipped (drives backward for +dq)", [("    joint_axis: Y\n    mass: 3.0\n    inertia: [ 0.01, 0,      0,\n               0,    0.1664, 0,\n               0,    0,      0.1636 ]\n    elements: &belt", "    joint_axis: -Y\n    mass: 3.0\n    inertia: [ 0.01, 0,      0,\n               0,    0.1664, 0,\n               0,    0,      0.1636 ]\n    elements: &belt"), ("    translation: [0, 0.31, 0]\n    joint_type: pseudo_continuous_track\n    joint_axis: Y", "    translation: [0, 0.31, 0]\n    joint_type: pseudo_continuous_track\n    joint_axis: -Y")],
     "pass", ["drives backward for +dq"]),
    ("scout", "tracks staggered fore-aft", [("translation: [0, -0.31, 0]", "translation: [0.08, -0.31, 0]")], "pass", []),
    ("scout", "turret off the centre line", [("translation: [0.1, 0, 0.07]", "translation: [0.1, 0.12, 0.07]")], "pass", []),
    ("scout", "a heavier hull with consistent inertia", [("    mass: 20.0\n    center_of_mass: [0, 0, 0]\n    # Solid box 0.7 x 0.5 x 0.14: m/12 (b² + c²), ...\n    inertia: [ 0.449333, 0,        0,\n               0,        0.849333, 0,\n               0,        0,        1.233333 ]", "    mass: 50.0\n    center_of_mass: [0, 0, 0]\n    inertia: [ 1.123333, 0,        0,\n               0,        2.123333, 0,\n               0,        0,        3.083333 ]")], "pass", []),
    ("skid", "the skidder as written (axes -Y on both tracks)", [], "pass", ["drives backward for +dq"]),
    # --- the same in the MuJoCo cross-check: the same dq to both tracks in both engines ---------------
    ("scout", "right track axis flipped (--cross-check mujoco)", [RIGHT_FLIPPED], "fail",
     ["tracks drive against each other", r"re:FAIL  MuJoCo: drive dq = \+1 on both tracks: heading drift[^\n]*\n"
      r"(      [^\n]*\n)*?      tracks drive against each other: \"BELT_B\" \(axis \(0, 1, 0\) in the root\s+frame\)\s+"
      r"drives\s+toward\s+\+X\s+and\s+\"BELT_A\"\s+\(axis\s+\(0,\s+-1,\s+0\)\)\s+toward\s+-X",
      "FAIL  Simbody: drive dq = +1 on both tracks: heading drift",
      "SKIP  MuJoCo vs Simbody: drive dq = +1 on both tracks: speed and time to 90 %",
      "re:PASS  MuJoCo vs Simbody: drive dq = \\+1 on both tracks: yaw rate"], ["--cross-check", "mujoco"]),
    ("scout", "both tracks flipped (--cross-check mujoco)", [RIGHT_FLIPPED, LEFT_FLIPPED], "pass",
     [r"re:PASS  MuJoCo: drive dq = \+1 on both tracks: heading drift[^\n]*\n(      [^\n]*\n)*?      drives backward for \+dq",
      r"re:PASS  MuJoCo vs Simbody: drive dq = \+1 on both tracks: speed\s+measured\s+-(1|0\.99999\d*|1\.00000\d*) m/s\s+expected\s+-1 "],
     ["--cross-check", "mujoco"]),
    ("scout", "ScoutTank as written (--cross-check mujoco)", [], "pass",
     [r"re:PASS  MuJoCo vs Simbody: drive dq = \+1 on both tracks: speed\s+measured\s+(1|0\.99999\d*|1\.00000\d*) m/s\s+expected\s+1 ",
      "PASS  MuJoCo: drive dq = +1 on both tracks: heading drift"], ["--cross-check", "mujoco"]),
    # --- checks that cannot apply: said ------------------------------------------------------------
    ("scout", "no turret (tower and cannon welded)", [("    joint_type: revolute\n    joint_id: 0", "    joint_type: fixed"), ("    joint_type: revolute\n    joint_id: 1", "    joint_type: fixed")],
     "skip", ["SKIP  turret: yaw tracking, final error and chassis reaction: no revolute joint about the vertical", "SKIP  turret: pitch sag and step response: no turret yaw joint"]),
    ("scout", "a tilted yaw axis", [("    joint_axis: Z\n    joint_range: unlimited", "    joint_axis: [0, 0.198669, 0.980067]\n    joint_range: unlimited")],
     "skip", ["SKIP  turret: yaw tracking, final error and chassis reaction: no revolute joint about the vertical"]),
    ("scout", "an unlimited pitch range", [("joint_range: [-30, 5]", "joint_range: unlimited")],
     "skip", ["SKIP  turret: pitch stays below its upper limit + 1°: the range of \"CANNON\" is unlimited",
              "SKIP  turret: pitch stays above its lower limit − 1°: the range of \"CANNON\" is unlimited"]),
    ("skid", "no turret at all (the skidder)", [], "pass", ["SKIP  turret: pitch sag and step response"]),
    # --- bodysim check: an arm (fixed root) and Choreonoid's conveyor (G8) ----------------------------
    ("arm", "the arm as written", [], "pass",
     ["PASS  gravity load on the held joints: worst sag error", "PASS  joint ranges: worst overshoot of a prismatic",
      "SKIP  drop and settle [G5]: the root is fixed"]),
    ("arm", "a reversed elbow range", [("joint_range: [-135, 135]", "joint_range: [135, -135]")],
     "refuse", ["arm.body:{line}:", "[joint-range-reversed]"]),
    ("arm", "a massless forearm", [("        mass: 1.0\n", "        mass: 0.0\n")],
     "refuse", ["link \"FOREARM\" moves (a revolute joint) but has zero mass", "[inertia-nonpositive-mass]"]),
    # A fixed root bolted below the floor: G9 (determinism) runs without it, and says so; with the
    # floor it threw the links out and stopped on the step budget after 11 s of CPU.
    ("arm", "the arm bolted 0.5 m below the floor", [("  - name: BASE\n    joint_type: fixed\n",
                                                      "  - name: BASE\n    translation: [0, 0, -0.5]\n    joint_type: fixed\n")],
     "pass", [r're:(?s)PASS  determinism: .*?\(without the floor: the root is fixed, and link "SHOULDER" starts 0\.42 m\s+inside it\) \[G9\]',
              r're:(?s)PASS  convergence: .*?\(without the\s+floor: the root is fixed']),
    ("arm", "an unlimited shoulder", [("joint_range: [-170, 170]", "joint_range: unlimited")],
     "skip", ["SKIP  joint ranges of \"SHOULDER\" [G6]: unlimited ranges: no stop to test"]),
    ("conveyor", "the conveyor as written (axis -Y: a box on it moves toward -X)", [], "pass",
     [r"re:(?s)PASS  surface velocity of .*?velocity v_x.*?\[G8\]\s+measured\s+-0\.5 m/s\s+expected\s+-0\.5 "]),
    ("conveyor", "the conveyor's axis flipped (+Y: toward +X)", [("jointAxis: -Y", "jointAxis: Y")], "pass",
     [r"re:(?s)PASS  surface velocity of .*?velocity v_x.*?\[G8\]\s+measured\s+0\.5 m/s\s+expected\s+0\.5 "]),
    ("conveyor", "the belt sunk below the base's top", [("translation: [ 0.0, 0.0, 0.15 ]", "translation: [ 0.0, 0.0, -0.05 ]")],
     "skip", ["SKIP  surface velocity of \"TRACK\" at dq = +0.5: a box on its top [G8]: link \"BASE\" reaches"]),
]

OUTCOME_EXIT = {"fail": 1, "pass": 0, "skip": 0, "refuse": 2}


def run_mutant(bodysim, paths, work, index, mutant):
    base, name, edits, expected, texts = mutant[:5]
    options = mutant[5] if len(mutant) > 5 else []
    path, command = BASES[base]
    with open(paths[path], encoding="utf-8") as f:
        text = f.read()
    line = None
    for old, new in edits:
        if text.count(old) != 1:
            return None, f"edit matches {text.count(old)} times: {old[:60]!r}"
        # The line of the edit's first changed character: where a finding about it points.
        start = text.index(old)
        first_change = next((i for i, (a, b) in enumerate(zip(old, new)) if a != b), min(len(old), len(new)))
        line = text[:start + first_change].count("\n") + 1
        text = text.replace(old, new)
    target = os.path.join(work, f"mutant_{index:02d}_{os.path.basename(path)}")
    with open(target, "w", encoding="utf-8") as f:
        f.write(text)
    proc = subprocess.run([bodysim, *command, "--no-config", *options, target], capture_output=True, text=True,
                          timeout=600)
    out = proc.stdout + proc.stderr
    got = {1: "fail", 2: "refuse"}.get(proc.returncode, "pass" if proc.returncode == 0 else f"exit {proc.returncode}")
    if got == "pass" and re.search(r"^SKIP  ", proc.stdout, re.M) and expected == "skip":
        got = "skip"
    missing = []
    for t in texts:
        t = t.replace("{line}", str(line))
        if t.startswith("re:") and re.search(t[3:], out):
            continue
        # Lines are wrapped at 100 columns: a text may run on over a line break.
        if t not in out and " ".join(t.split()) not in " ".join(out.split()):
            missing.append(t)
    if expected == "fail" and not any(l.startswith("FAIL") for l in proc.stdout.splitlines()):
        missing.append("a FAIL line")
    if expected in ("pass", "skip") and re.search(r"^FAIL", proc.stdout, re.M):
        missing.append("no FAIL line")
    if expected == "refuse" and "nothing was simulated" not in out:
        missing.append("nothing was simulated")
    ok = got == expected and not missing and proc.returncode == OUTCOME_EXIT[expected]
    detail = "" if ok else f"missing {missing}\n{out[-3000:]}"
    return (got, ok), detail


def main():
    if len(sys.argv) not in (6, 7) or (len(sys.argv) == 7 and sys.argv[6] != "--with-mujoco"):
        print(__doc__)
        return 2
    bodysim, examples, data, shared, work = sys.argv[1:6]
    with_mujoco = len(sys.argv) == 7
    os.makedirs(work, exist_ok=True)
    roots = {"examples": examples, "data": data, "shared": shared}
    paths = {path: os.path.join(roots[path.split("/", 1)[0]], path.split("/", 1)[1]) for path, _ in BASES.values()}
    rows, failures, not_run = [], 0, 0
    for index, mutant in enumerate(MUTANTS):
        if "--cross-check" in (mutant[5] if len(mutant) > 5 else []) and not with_mujoco:
            rows.append((f"{mutant[0]}: {mutant[1]}", mutant[3], "not run", "bodysim has no MuJoCo"))
            not_run += 1
            continue
        result, detail = run_mutant(bodysim, paths, work, index, mutant)
        got, ok = result if result else ("edit error", False)
        failures += 0 if ok else 1
        rows.append((f"{mutant[0]}: {mutant[1]}", mutant[3], got, "ok" if ok else "WRONG"))
        if not ok:
            print(f"--- {mutant[0]}: {mutant[1]}: {detail}")
    width = max(len(r[0]) for r in rows)
    print(f"| {'mutant':<{width}} | expected | got    | |")
    for r in rows:
        print(f"| {r[0]:<{width}} | {r[1]:<8} | {r[2]:<6} | {r[3]} |")
    print(f"mutation score: {len(rows) - not_run - failures} of {len(rows) - not_run} mutants get their expected "
          f"outcome" + (f"; {not_run} not run (bodysim built without MuJoCo)" if not_run else ""))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
