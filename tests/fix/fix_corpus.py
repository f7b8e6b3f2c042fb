#!/usr/bin/env python3
"""`bodycheck --fix --upgrade` on every corpus model, each in a copy of the corpus.

usage: fix_corpus.py BODYCHECK BODYINFO CORPUS_DIR WORK_DIR

For each model (every *.body of the corpus), in a fresh copy of its top-level folder (and of
the sibling folders its includes reach):
  1. `bodycheck --fix --upgrade --fix-includes MODEL` exits 0 or 1 (never 2: nothing refused);
  2. the copy loads to the same model: `bodyinfo --format yaml` of the original and of the copy
     are equal, strings exactly and numbers within 1e-12 relative (1e-12 absolute below 1),
     the `messages` entry (diagnostics, which the fix is meant to change) aside;
  3. the copy has no load-legacy-key finding left (bodycheck --format json);
  4. every line that changed holds an edit: its line number is the line of a safe or upgrade
     fix-it that `bodycheck --format json` reported on the original for that file, and no
     file gained or lost lines;
  5. idempotence: a second `--fix --upgrade --fix-includes` changes no byte of any file.
The corpus itself is only read (copied to WORK_DIR, which is emptied first).
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys

import yaml


class _Loader(yaml.SafeLoader):
    pass


_Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^(?:[-+]?[0-9][0-9_]*(?:\.[0-9_]*)?(?:[eE][-+]?[0-9]+)?|[-+]?\.[0-9_]+(?:[eE][-+]?[0-9]+)?"
               r"|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$"),
    list("-+0123456789."))


def same(a, b, path="model"):
    """None when equal, else where they differ."""
    if isinstance(a, dict) and isinstance(b, dict):
        if a.keys() != b.keys():
            return f"{path}: keys {sorted(a)} != {sorted(b)}"
        for k in a:
            d = same(a[k], b[k], f"{path}.{k}")
            if d:
                return d
        return None
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return f"{path}: {len(a)} != {len(b)} items"
        for i, (x, y) in enumerate(zip(a, b)):
            d = same(x, y, f"{path}[{i}]")
            if d:
                return d
        return None
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        a, b = float(a), float(b)
        if a == b or (math.isnan(a) and math.isnan(b)):
            return None
        if abs(a - b) <= 1e-12 * max(1.0, abs(a), abs(b)):
            return None
        return f"{path}: {a!r} != {b!r}"
    return None if a == b else f"{path}: {a!r} != {b!r}"


def bodyinfo(tool, model):
    out = subprocess.run([tool, "--format", "yaml", model], capture_output=True, text=True)
    data = yaml.load(out.stdout, Loader=_Loader) or {}
    data.pop("messages", None)
    return data


def findings(bodycheck, model):
    out = subprocess.run([bodycheck, "--format", "json", "--no-config", model], capture_output=True, text=True)
    return json.loads(out.stdout)["diagnostics"]


def snapshot(folder):
    files = {}
    for root, _, names in os.walk(folder):
        for name in names:
            path = os.path.join(root, name)
            with open(path, "rb") as f:
                files[os.path.relpath(path, folder)] = f.read()
    return files


def main():
    bodycheck, tool, corpus, work = sys.argv[1:5]
    corpus = os.path.join(corpus, "choreonoid")
    models = sorted(os.path.relpath(os.path.join(r, n), corpus) for r, _, ns in os.walk(corpus) for n in ns
                    if n.endswith(".body"))
    failures = []
    checked = edits_seen = 0
    for model in models:
        top = model.split(os.sep)[0]
        shutil.rmtree(work, ignore_errors=True)
        os.makedirs(work)
        if top == model:  # a model at the top of the corpus: copy just it
            shutil.copy(os.path.join(corpus, model), work)
        else:
            # The model's folder, and the sibling folders its includes climb into (UR5-2F85
            # includes ../Robotiq/2F-85.body).
            with open(os.path.join(corpus, model), encoding="utf-8", errors="replace") as f:
                siblings = set(re.findall(r"\.\./([^/\"'\s]+)/", f.read()))
            for folder in {top} | siblings:
                if os.path.isdir(os.path.join(corpus, folder)):
                    shutil.copytree(os.path.join(corpus, folder), os.path.join(work, folder))
        # The shared corpus is read-only (mode 0444), and --fix refuses read-only files.
        for root, _, names in os.walk(work):
            for name in names:
                path = os.path.join(root, name)
                os.chmod(path, os.stat(path).st_mode | 0o200)
        original_model = os.path.join(corpus, model)
        copy_model = os.path.join(work, model)
        before = snapshot(work)
        # Fix-it lines reported on the original, per file relative to the copy root.
        edit_lines = {}
        for d in findings(bodycheck, copy_model):
            for f in d["fixes"]:
                if f["safety"] in ("safe", "upgrade"):
                    rel = os.path.relpath(os.path.realpath(f["file"]), os.path.realpath(work))
                    edit_lines.setdefault(rel, set()).add(f["line"])
        run = subprocess.run([bodycheck, "--fix", "--upgrade", "--fix-includes", "-q", "--no-config", copy_model],
                             capture_output=True, text=True)
        if run.returncode not in (0, 1):
            failures.append(f"{model}: bodycheck --fix exited {run.returncode}: {run.stderr.strip()[:500]}")
            continue
        after = snapshot(work)
        for rel, data in after.items():
            old = before.get(rel)
            if old == data:
                continue
            a, b = old.decode().split("\n"), data.decode().split("\n")
            if len(a) != len(b):
                failures.append(f"{model}: {rel} has {len(b)} lines instead of {len(a)}")
                continue
            for number, (x, y) in enumerate(zip(a, b), start=1):
                if x != y:
                    edits_seen += 1
                    if number not in edit_lines.get(rel, set()):
                        failures.append(f"{model}: {rel}:{number} changed without a fix-it there: {x!r} -> {y!r}")
        difference = same(bodyinfo(tool, original_model), bodyinfo(tool, copy_model))
        if difference:
            failures.append(f"{model}: the fixed copy loads a different model: {difference}")
        legacy = [d for d in findings(bodycheck, copy_model) if d["rule"] == "load-legacy-key"]
        if legacy:
            failures.append(f"{model}: {len(legacy)} load-legacy-key findings left, first at "
                            f"{legacy[0]['file']}:{legacy[0]['line']}: {legacy[0]['message']}")
        again = subprocess.run([bodycheck, "--fix", "--upgrade", "--fix-includes", "-q", "--no-config", copy_model],
                               capture_output=True, text=True)
        if snapshot(work) != after:
            failures.append(f"{model}: a second --fix changed the files again ({again.stderr.strip()[:300]})")
        checked += 1
    shutil.rmtree(work, ignore_errors=True)
    print(f"{checked} of {len(models)} corpus models fixed and upgraded; {edits_seen} changed lines, each at a fix-it")
    for f in failures:
        print("FAIL", f)
    if checked < 50:
        print("FAIL: fewer than 50 corpus models were checked")
        return 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
