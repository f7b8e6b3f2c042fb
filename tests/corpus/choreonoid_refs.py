#!/usr/bin/env python3
"""Compares bodyinfo on body files with what Choreonoid's own loaders made of the same files
(tests/corpus/choreonoid_dump, built with Choreonoid's URDF loader; references in the schema of
shared/corpus/README.md): wrappers around URDFs (`model_file: X.urdf`, tests/data/urdf_choreonoid)
and small body files of the value forms of docs/format-notes.md (tests/data/body_choreonoid).

usage: choreonoid_refs.py BODYINFO MODEL_ROOT REF_ROOT [WRAPPER...]
For each REF_ROOT/**/W.ref.yaml (or only the WRAPPER paths given, relative to MODEL_ROOT), runs
BODYINFO --format yaml on MODEL_ROOT/**/W.body and sorts the pair into one outcome:
  match            Choreonoid loads it; bodyinfo exits 0 with every field of the schema equal
                   (link order, joints, mass data, frames, boxes, devices, counts, model name)
  both refuse      Choreonoid refuses it; bodyinfo reports an error (exit 1 or 2)
  values differ    both load it, some field differs (each difference is printed)
  bodyfmt refuses  Choreonoid loads it, bodyinfo reports an error or exits 2
  bodyfmt loads    Choreonoid refuses it, bodyinfo exits 0
A file may declare a difference that docs/format-notes.md (or an open question) accounts for
with a line `# known difference: OUTCOME (why)`: then that outcome, and only that one, passes
(counted as "known difference"), so the test fails once the difference goes away too.
Prints one line per file, then the count of each outcome. Exit 0 when every file is a match,
both refuse or its declared known difference, 1 otherwise, 2 on a usage error.

`messages` is left out: Choreonoid's are its own wording (and its Debug lines), bodyinfo's are
its findings. Tolerances are compare_refs.py's (the corpus README's): 1e-9 relative plus 1e-12
absolute, boxes within 1e-3 m or 1 % of their size.
"""
import pathlib
import subprocess
import sys

import yaml

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "corpus" / "choreonoid_dump"))
import compare_refs  # noqa: E402  (field-by-field comparison of two references)

OUTCOMES = ("match", "both refuse", "values differ", "bodyfmt refuses", "bodyfmt loads", "known difference")
KNOWN = "# known difference:"


def declared_difference(wrapper):
    """The outcome a `# known difference: OUTCOME (why)` line declares, or None."""
    for line in wrapper.read_text(errors="replace").splitlines():
        if line.startswith(KNOWN):
            rest = line[len(KNOWN):].strip()
            return next((o for o in OUTCOMES[2:5] if rest.startswith(o)), rest)
    return None


def load(text):
    return yaml.load(text, Loader=compare_refs._Loader)


def judge(bodyinfo, wrapper, ref_file):
    """Returns (outcome, details) for one wrapper and its Choreonoid reference."""
    ref = load(ref_file.read_text()) or {}
    try:
        run = subprocess.run([bodyinfo, "--format", "yaml", str(wrapper)], capture_output=True, text=True,
                             timeout=300)
    except subprocess.TimeoutExpired:
        return ("bodyfmt refuses" if ref.get("loaded") else "both refuse"), ["bodyinfo timed out"]
    errors = [line for line in run.stderr.splitlines() if ": error:" in line]
    refused = run.returncode == 2 or bool(errors)
    if not ref.get("loaded"):
        if refused:
            return "both refuse", []
        return "bodyfmt loads", [f"Choreonoid: {ref.get('messages', '')!r}"[:300]]
    if refused:
        return "bodyfmt refuses", [f"exit {run.returncode}"] + errors[:3]
    ours = load(run.stdout)
    if not isinstance(ours, dict):
        return "bodyfmt refuses", [f"no YAML model (exit {run.returncode})"]
    ref.pop("messages", None)
    ours.pop("messages", None)
    problems = compare_refs.diff(ref, ours)
    return ("values differ", problems) if problems else ("match", [])


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    bodyinfo, model_root, ref_root = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    if len(sys.argv) > 4:
        pairs = [(model_root / w, ref_root / (w[: -len(".body")] + ".ref.yaml")) for w in sys.argv[4:]]
    else:
        pairs = [(model_root / r.relative_to(ref_root).as_posix().replace(".ref.yaml", ".body"), r)
                 for r in sorted(ref_root.rglob("*.ref.yaml"))]
    counts = dict.fromkeys(OUTCOMES, 0)
    for wrapper, ref_file in pairs:
        if not wrapper.is_file() or not ref_file.is_file():
            print(f"{wrapper}: missing {'wrapper' if not wrapper.is_file() else ref_file}")
            counts["values differ"] += 1
            continue
        outcome, details = judge(bodyinfo, wrapper, ref_file)
        declared = declared_difference(wrapper)
        if declared is not None:
            if outcome == declared:
                outcome = "known difference"
                details = [f"declared: {declared}"] + details
            else:
                details = [f"declared known difference {declared!r} not seen"] + details
                if outcome in ("match", "both refuse"):
                    outcome = "values differ"  # the declaration is stale: fail
        counts[outcome] += 1
        print(f"{wrapper.relative_to(model_root)}: {outcome}")
        for line in details:
            print(f"    {line}")
    print("choreonoid_refs: " + ", ".join(f"{n} {o}" for o, n in counts.items()))
    passed = counts["match"] + counts["both refuse"] + counts["known difference"]
    sys.exit(0 if passed == len(pairs) and pairs else 1)


if __name__ == "__main__":
    main()
