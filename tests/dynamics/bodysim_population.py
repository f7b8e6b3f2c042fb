#!/usr/bin/env python3
"""`bodysim check` on a population of random valid models (random_models.py; free roots, or
with --fixed-root the same models fixed to the world): every
model is first shown valid (bodycheck: no finding at all), then `bodysim check` (with
--cross-check mujoco when asked) must fail none of its checks. A check that cannot apply is a
SKIP with its reason, which is counted, not failed. Prints the outcome counts per check and,
for every model that failed a check or was refused, its seed, what it is and the failing lines.

CI runs a small fixed-seed sample: the first seeds and the seeds a fix was shown on (--also);
by hand, any number of models from any seed:
  bodysim_population.py BODYSIM BODYCHECK WORKDIR [--count N] [--seed S] [--also S1,S2,...] [--cross-check]
  BODYFMT_POPULATION=200 ... (overrides --count)
Exit 0 when no model failed a check, 1 otherwise, 2 on a usage error."""
import argparse
import collections
import os
import pathlib
import re
import resource
import subprocess
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import random_models  # noqa: E402

SCALE = float(os.environ.get("BODYFMT_TIME_SCALE", "1"))
OUTCOME = re.compile(r"^(PASS|FAIL|SKIP)  (.*)$")


def records(text):
    """bodysim's report, one record per check: indented continuation lines joined to their check."""
    out = []
    for line in text.splitlines():
        if line[:1] == " " and out:
            out[-1] += " " + line.strip()
        else:
            out.append(line)
    return out


def check_key(name):
    """The check a record is about, without the model's numbers: parentheses and numbers out,
    cut at the reason or the measured values."""
    name = re.split(r" measured | \[G\d\]", name)[0]
    name = re.split(r": (?=[a-z][^:]*$)", name)[0] if name.startswith("SKIP") else name
    name = re.sub(r"\([^()]*\)", "", name)
    name = re.sub(r"\([^()]*\)", "", name)
    name = re.sub(r"[-+]?\d[\d.e+-]*", "#", name)
    return re.sub(r"\s+", " ", name).strip()[:90]


def cpu_seconds():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("bodysim")
    parser.add_argument("bodycheck")
    parser.add_argument("workdir")
    parser.add_argument("--count", type=int, default=6)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--also", default="", help="comma-separated seeds run besides the range")
    parser.add_argument("--cross-check", action="store_true", help="bodysim check --cross-check mujoco")
    parser.add_argument("--fixed-root", action="store_true", help="the same models with their root fixed")
    parser.add_argument("--keep-going", action="store_true", help="(always on) kept for symmetry with other tests")
    args = parser.parse_args()
    count = int(os.environ.get("BODYFMT_POPULATION", args.count))
    work = pathlib.Path(args.workdir)
    work.mkdir(parents=True, exist_ok=True)  # a fresh build tree has no such folder yet

    counts = collections.defaultdict(collections.Counter)  # check -> outcome -> models
    failed_models, refused, invalid = [], [], []
    start = cpu_seconds()
    try:
        also = [int(s) for s in args.also.split(",") if s.strip()]
    except ValueError:
        parser.error(f"--also takes comma-separated seeds, not {args.also!r}")
    seeds = list(range(args.seed, args.seed + count)) + [s for s in also if not args.seed <= s < args.seed + count]
    for seed in seeds:
        text, description = random_models.generate(seed, args.fixed_root)
        path = work / f"random{seed}.body"
        path.write_text(text, encoding="utf-8")
        check = subprocess.run([args.bodycheck, "--no-config", str(path)], capture_output=True, text=True)
        if check.returncode != 0 or "0 errors, 0 warnings, 0 notes" not in check.stdout + check.stderr:
            invalid.append((seed, description, (check.stdout + check.stderr).strip()))
            continue
        command = [args.bodysim, "check", "--no-config", str(path)]
        if args.cross_check:
            command += ["--cross-check", "mujoco"]
        try:
            run = subprocess.run(command, capture_output=True, text=True, timeout=120 * SCALE)
        except subprocess.TimeoutExpired:
            refused.append((seed, description, f"no answer within {120 * SCALE:g} s"))
            continue
        failing = []
        for record in records(run.stdout):
            m = OUTCOME.match(record)
            if not m:
                continue
            counts[check_key(m.group(2))][m.group(1)] += 1
            if m.group(1) == "FAIL":
                failing.append(record)
        if run.returncode == 2 or (run.returncode == 1 and not failing):
            refused.append((seed, description, (run.stderr.strip() or run.stdout.strip()).splitlines()[-1:]))
        if failing:
            failed_models.append((seed, description, failing))
    used = cpu_seconds() - start

    mode = "bodysim check --cross-check mujoco" if args.cross_check else "bodysim check"
    mode += ", fixed roots" if args.fixed_root else ""
    extra = [s for s in seeds if not args.seed <= s < args.seed + count]
    print(f"{mode} on {len(seeds)} random valid models (seeds {args.seed}..{args.seed + count - 1}"
          f"{''.join(f', {s}' for s in extra)}), {used:.1f} s CPU")
    print(f"{'PASS':>5} {'FAIL':>5} {'SKIP':>5}  check")
    for key in sorted(counts):
        c = counts[key]
        print(f"{c['PASS']:5d} {c['FAIL']:5d} {c['SKIP']:5d}  {key}")
    print(f"models: {len(seeds) - len(failed_models) - len(refused) - len(invalid)} passed, "
          f"{len(failed_models)} failed a check, {len(refused)} refused or timed out, "
          f"{len(invalid)} not valid (a generator defect)")
    if args.cross_check:
        simbody_only = sum(1 for _, _, lines in failed_models if any("MuJoCo vs Simbody" not in l for l in lines))
        print(f"models failing a check of Simbody alone (as plain bodysim check would): {simbody_only}")
    for seed, description, lines in failed_models:
        print(f"\nFAILED {description}")
        for line in lines:
            print("  " + line)
    for seed, description, why in refused:
        print(f"\nREFUSED {description}: {why}")
    for seed, description, why in invalid:
        print(f"\nINVALID {description}: {why}")
    return 1 if failed_models or refused or invalid else 0


if __name__ == "__main__":
    sys.exit(main())
