#!/usr/bin/env python3
"""Opt-in (not run by ctest: it needs the Choreonoid mirror): every .scen scene file of
Choreonoid's share/model must load as shapes of a body that names it, with no error.

    choreonoid_scen.py [MIRROR_GIT_DIR] [BUILD_DIR]

MIRROR_GIT_DIR defaults to /work/.mirror/choreonoid+choreonoid/repo (a bare repository),
BUILD_DIR to ./build. Each scene file's folder (with what its Resource nodes name: meshes,
textures) is copied out of HEAD with `git show` into a temporary folder, a one-line body file
beside the scene file names it by a Resource node, and bodyinfo must exit 0 with no error or
fatal diagnostic (its YAML output gives the link's box). A scene file counts as "shapes" when the link's visual box
is not empty; one without a shape (text.scen holds only a Text node, which has no meaning in a
body) must at least say why with a located note or warning. Prints one line per file and the
counts; exits 1 when a file fails.
"""
import os
import re
import subprocess
import sys
import tempfile

MIRROR = sys.argv[1] if len(sys.argv) > 1 else "/work/.mirror/choreonoid+choreonoid/repo"
BUILD = sys.argv[2] if len(sys.argv) > 2 else "build"
BODYINFO = os.path.join(BUILD, "bodyinfo")

BODY = ("format: ChoreonoidBody\nformat_version: 2.0\nname: {name}\nlinks:\n"
        "  - {{name: BASE, mass: 1, inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1], "
        "elements: [{{type: Resource, uri: {uri}}}]}}\n")
LOCATED = re.compile(r"^\S+:\d+:\d+: (error|fatal error|warning|note): .*\[([a-z0-9-]+)\]$", re.M)


def git(*args):
    return subprocess.run(["git", "-C", MIRROR, *args], capture_output=True, check=False)


def extract_folder(folder, out):
    """Copies every file under `folder` at HEAD into `out`; returns (copied, unreadable)."""
    listing = git("ls-tree", "-r", "--name-only", "HEAD", "--", folder).stdout.decode().split("\n")
    copied = unreadable = 0
    for path in filter(None, listing):
        blob = git("show", "HEAD:" + path)
        if blob.returncode != 0:  # a blob the mirror does not hold
            unreadable += 1
            continue
        target = os.path.join(out, path)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        with open(target, "wb") as f:
            f.write(blob.stdout)
        copied += 1
    return copied, unreadable


def main():
    if not os.access(BODYINFO, os.X_OK):
        sys.exit(f"no bodyinfo at {BODYINFO}: build it first (cmake --build {BUILD} --target bodyinfo)")
    files = git("ls-tree", "-r", "--name-only", "HEAD", "--", "share/model").stdout.decode().split("\n")
    scenes = sorted(p for p in files if p.endswith(".scen"))
    if not scenes:
        sys.exit(f"no .scen file under share/model in {MIRROR}")
    counts = {"scene files": len(scenes), "loaded without error": 0, "with shapes": 0, "failed": 0}
    with tempfile.TemporaryDirectory(prefix="choreonoid_scen_") as tmp:
        copied = unreadable = 0
        for folder in sorted({os.path.dirname(s) for s in scenes}):
            c, u = extract_folder(folder, tmp)
            copied += c
            unreadable += u
        for scene in scenes:
            name = os.path.splitext(os.path.basename(scene))[0]
            body = os.path.join(tmp, os.path.dirname(scene), f"wrap_{name}.body")
            with open(body, "w") as f:
                f.write(BODY.format(name=name, uri=os.path.basename(scene)))
            # The text run prints every finding, notes too; the YAML run the link's box.
            run = subprocess.run([BODYINFO, body], capture_output=True, text=True, timeout=300)
            found = LOCATED.findall(run.stderr)
            yaml_run = subprocess.run([BODYINFO, "--format", "yaml", body], capture_output=True, text=True,
                                      timeout=300)
            box = re.search(r"visual_bbox: \[([^\]]*)\]", yaml_run.stdout)
            errors = [rule for severity, rule in found if severity in ("error", "fatal error")]
            has_shapes = box is not None and "inf" not in box.group(1)
            rules = sorted({rule for _, rule in found})
            ok = run.returncode == 0 and not errors and (has_shapes or found)
            if run.returncode == 0 and not errors:
                counts["loaded without error"] += 1
            if has_shapes:
                counts["with shapes"] += 1
            if not ok:
                counts["failed"] += 1
            print(f"{'ok  ' if ok else 'FAIL'} {scene}: exit {run.returncode}, "
                  f"{'visual box [' + box.group(1) + ']' if has_shapes else 'no shape'}"
                  f"{', findings: ' + ' '.join(rules) if rules else ''}")
            if not ok:
                print(run.stderr)
        print(f"{copied} files copied from the mirror ({unreadable} blobs it does not hold)")
    print(", ".join(f"{k}: {v}" for k, v in counts.items()))
    sys.exit(1 if counts["failed"] else 0)


main()
