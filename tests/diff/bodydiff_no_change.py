#!/usr/bin/env python3
"""No change means no output: rewrites of every corpus model that leave the model the same.

usage: bodydiff_no_change.py BODYDIFF BODYCHECK CORPUS_DIR WORK_DIR

The corpus is copied to WORK_DIR (emptied first); each rewrite is written beside its model, so
that relative URIs resolve as they do for the original. For every model that loads:
  - the model against itself, reformatted (4-space indent), with its mapping keys sorted, with
    every legacy/snake_case key spelling swapped, with every alias expanded, with equal
    subtrees turned into anchors and aliases, and after `bodycheck --fix --upgrade`: bodydiff
    exits 0 and prints nothing (stdout and stderr);
  - each rewrite must differ from the original text (else the case proves nothing), and the
    same rewrite with the first `mass` doubled must exit 1 with output (else the rewrite never
    reaches the model).
"""
import os
import shutil
import subprocess
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import yaml_variants as yv  # noqa: E402


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True)


def main():
    bodydiff, bodycheck, corpus, work = sys.argv[1:5]
    if os.path.isdir(os.path.join(corpus, "choreonoid")):  # the shared corpus: models and references
        corpus = os.path.join(corpus, "choreonoid")
    shutil.rmtree(work, ignore_errors=True)
    shutil.copytree(corpus, work, ignore=shutil.ignore_patterns("reference"))
    models = sorted(os.path.join(d, f) for d, _, fs in os.walk(work) for f in fs if f.endswith(".body"))
    failures, cases, skipped = [], 0, []
    for model in models:
        if os.path.basename(model).startswith("__"):
            continue
        rel = os.path.relpath(model, work)
        same = run([bodydiff, model, model])
        if same.returncode == 2:
            skipped.append(rel)
            continue
        if same.returncode != 0 or same.stdout or same.stderr:
            failures.append(f"{rel}: against itself: exit {same.returncode}\n{same.stdout}{same.stderr}")
            continue
        text = open(model, encoding="utf-8").read()
        tree = yv.load(text)
        variants = {
            "reformatted": yv.dump(tree, indent=4),
            "sorted-keys": yv.dump(tree, sort_keys=True),
            "respelled": yv.dump(yv.respelled(tree)),
            "expanded": yv.dump(yv.expanded(tree)),
            "anchored": yv.dump(yv.with_anchors(tree)),
        }
        mutated = yv.first_mass_doubled(tree)
        for name, variant in variants.items():
            cases += 1
            if variant == text:
                failures.append(f"{rel} {name}: the rewrite is the original text")
                continue
            path = os.path.join(os.path.dirname(model), f"__{name}_{os.path.basename(model)}")
            with open(path, "w", encoding="utf-8") as f:
                f.write(variant)
            r = run([bodydiff, model, path])
            if r.returncode != 0 or r.stdout or r.stderr:
                failures.append(f"{rel} {name}: exit {r.returncode}\n{r.stdout[:3000]}{r.stderr[:2000]}")
            if mutated is not None:
                tweak = {"reformatted": lambda t: t, "sorted-keys": lambda t: t, "respelled": yv.respelled,
                         "expanded": lambda t: t, "anchored": yv.with_anchors}[name]
                with open(path, "w", encoding="utf-8") as f:
                    f.write(yv.dump(tweak(mutated), sort_keys=(name == "sorted-keys")))
                r = run([bodydiff, model, path])
                if r.returncode != 1 or "mass" not in r.stdout:
                    failures.append(f"{rel} {name} with a mass doubled: exit {r.returncode}, not reported")
        # bodycheck --fix --upgrade (format 1.0 -> 2.0, legacy keys renamed) on a copy
        cases += 1
        upgraded = os.path.join(os.path.dirname(model), f"__upgraded_{os.path.basename(model)}")
        shutil.copyfile(model, upgraded)
        fix = run([bodycheck, "--fix", "--upgrade", "--no-config", upgraded])
        if fix.returncode == 2:
            failures.append(f"{rel} upgrade: bodycheck --fix refused: {fix.stderr[:500]}")
        else:
            r = run([bodydiff, model, upgraded])
            if r.returncode != 0 or r.stdout or r.stderr:
                failures.append(f"{rel} upgraded: exit {r.returncode}\n{r.stdout[:3000]}{r.stderr[:2000]}")
    print(f"{len(models)} files, {len(skipped)} not loadable ({', '.join(skipped)}), {cases} rewrites, "
          f"{len(failures)} failures")
    for f in failures:
        print("FAIL", f)
    return 1 if failures or cases == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
