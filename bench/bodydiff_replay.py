#!/usr/bin/env python3
"""Replays the history of a Choreonoid repository's models through bodydiff (issue 28).

usage: bodydiff_replay.py REPO BODYDIFF BODYINFO WORK_DIR [--limit N]

REPO is a clone of choreonoid/choreonoid (a bare git directory will do). For every commit that
changes a `share/model/**/*.body` file (modified, not added or deleted), the model's top folder
(share/model/NAME) is written out at the parent and at the commit, and:
  - where `bodyinfo --format yaml` differs (numbers beyond 1e-9 relative, `messages` aside),
    bodydiff must report a change (exit 1);
  - where bodydiff reports nothing (exit 0), bodyinfo must be the same.
Prints the counts, and every pair that breaks either rule. Not part of ctest: it needs the
repository, which the project does not ship; without one it says so and exits 0 (skipped).
"""
import collections
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


def differs(a, b, tol=1e-9):
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() != b.keys() or any(differs(a[k], b[k], tol) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) != len(b) or any(differs(x, y, tol) for x, y in zip(a, b))
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        a, b = float(a), float(b)
        if a == b or (math.isnan(a) and math.isnan(b)):
            return False
        if not math.isfinite(a) or not math.isfinite(b):  # inf against a number: the bound is inf too
            return True
        return not abs(a - b) <= tol * max(1.0, abs(a), abs(b))
    return a != b


def git(repo, *args, **kw):
    return subprocess.run(["git", "-C", repo, *args], capture_output=True, **kw)


def write_tree(repo, rev, folder, dest):
    """The files of `folder` at `rev` under dest (blobs missing from a partial clone left out)."""
    listing = git(repo, "ls-tree", "-r", "-z", rev, "--", folder).stdout.split(b"\0")
    entries = []
    for line in listing:
        if not line:
            continue
        meta, path = line.split(b"\t", 1)
        mode, kind, obj = meta.split()
        if kind == b"blob":
            entries.append((obj.decode(), path.decode()))
    proc = subprocess.Popen(["git", "-C", repo, "cat-file", "--batch"], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
    for obj, path in entries:
        proc.stdin.write(obj.encode() + b"\n")
        proc.stdin.flush()
        header = proc.stdout.readline().split()
        if len(header) < 3 or header[1] == b"missing":
            continue
        data = proc.stdout.read(int(header[2]))
        proc.stdout.read(1)
        target = os.path.join(dest, path)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        with open(target, "wb") as f:
            f.write(data)
    proc.stdin.close()
    proc.wait()


def bodyinfo(tool, model):
    out = subprocess.run([tool, "--format", "yaml", "--no-config", model], capture_output=True, text=True)
    data = yaml.load(out.stdout, Loader=_Loader) or {}
    data.pop("messages", None)
    return data


def main():
    args = sys.argv[1:]
    limit = None
    if "--limit" in args:
        i = args.index("--limit")
        limit = int(args[i + 1])
        del args[i:i + 2]
    if len(args) != 4:
        print(__doc__)
        return 2
    repo, bodydiff, bodyinfo_tool, work = args
    if not os.path.isdir(repo) or git(repo, "rev-parse", "--git-dir").returncode != 0:
        print(f"skipped: no git repository at {repo}")
        return 0
    log = git(repo, "log", "--format=%H %P", "--", "share/model/**/*.body", text=True).stdout.split("\n")
    counts = dict(pairs=0, unloadable=0, info_differs=0, reported=0, info_same_reported=0, both_same=0,
                  missed=0, silent_but_different=0)
    problems = []
    # What bodydiff saw where bodyinfo (which shows no devices, materials or extra joints) did not.
    beyond_bodyinfo = collections.Counter()
    unloadable = []
    commits = [line.split() for line in log if line.strip()]
    if limit:
        commits = commits[:limit]
    for n, (commit, *parents) in enumerate(commits):
        if not parents:
            continue
        parent = parents[0]
        changed = git(repo, "diff", "--name-status", "--no-renames", parent, commit, "--",
                      "share/model/**/*.body", text=True).stdout.split("\n")
        for line in changed:
            parts = line.split("\t")
            if len(parts) != 2 or parts[0] != "M":
                continue
            path = parts[1]
            top = "/".join(path.split("/")[:3])  # share/model/NAME
            shutil.rmtree(work, ignore_errors=True)
            old_root, new_root = os.path.join(work, "old"), os.path.join(work, "new")
            write_tree(repo, parent, top, old_root)
            write_tree(repo, commit, top, new_root)
            old, new = os.path.join(old_root, path), os.path.join(new_root, path)
            if not os.path.exists(old) or not os.path.exists(new):
                continue
            counts["pairs"] += 1
            d = subprocess.run([bodydiff, old, new], capture_output=True, text=True)
            if d.returncode == 2:
                counts["unloadable"] += 1
                unloadable.append(f"{commit[:10]} {path}: {(d.stderr.splitlines() or [''])[0]}")
                continue
            a, b = bodyinfo(bodyinfo_tool, old), bodyinfo(bodyinfo_tool, new)
            info_differs = differs(a, b)
            reported = d.returncode == 1
            counts["info_differs"] += info_differs
            counts["reported"] += reported
            if info_differs and reported:
                pass
            elif info_differs and not reported:
                counts["missed"] += 1
                problems.append(f"MISSED {commit[:10]} {path}: bodyinfo differs, bodydiff silent")
            elif reported:
                counts["info_same_reported"] += 1
                j = subprocess.run([bodydiff, "--format", "json", old, new], capture_output=True, text=True)
                for c in json.loads(j.stdout)["changes"]:
                    beyond_bodyinfo[re.sub(r"\d+|'[^']*'", "#", c["field"])] += 1
            else:
                counts["both_same"] += 1
            if not reported and (d.stdout or d.stderr):
                counts["silent_but_different"] += 1
                problems.append(f"OUTPUT {commit[:10]} {path}: exit 0 with output")
        print(f"[{n + 1}/{len(commits)}] {commit[:10]} {counts}", file=sys.stderr, flush=True)
    print(" ".join(f"{k}={v}" for k, v in counts.items()))
    print("fields reported where bodyinfo is the same:",
          ", ".join(f"{k} {v}" for k, v in beyond_bodyinfo.most_common()))
    for u in unloadable:
        print("UNLOADABLE", u)
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
