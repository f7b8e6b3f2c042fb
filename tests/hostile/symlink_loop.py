#!/usr/bin/env python3
"""A symbolic link loop on the command line is reported as one, by every tool (issue 45, item 3).

    symlink_loop.py BIN_DIR

`ln -s loop.body loop.body; TOOL loop.body` must exit 2 saying "too many levels of symbolic
links" (the bounded reader's words, libbodyfmt/src/io/read_file.cpp), not "no such file"; and
so must a SubBody whose uri is such a loop, at the line that names it.
"""
import os
import subprocess
import sys
import tempfile

LOOP_TEXT = "too many levels of symbolic links"


def main():
    bin_dir = sys.argv[1]
    tool = lambda t: os.path.join(bin_dir, t)
    failures = []
    with tempfile.TemporaryDirectory() as folder:
        loop = os.path.join(folder, "loop.body")
        os.symlink("loop.body", loop)
        urdf_loop = os.path.join(folder, "loop.urdf")
        os.symlink("loop.urdf", urdf_loop)
        good = os.path.join(folder, "good.body")
        with open(good, "w") as f:
            f.write(
                "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n"
                "  - {name: base, joint_type: free, mass: 1, inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1]}\n"
            )
        out = lambda name: os.path.join(folder, name)
        runs = {
            "bodyinfo": [tool("bodyinfo"), loop],
            "bodycheck": [tool("bodycheck"), loop],
            "bodycheck json": [tool("bodycheck"), "--format", "json", loop],
            "body2urdf": [tool("body2urdf"), loop, "-o", out("a.urdf")],
            "body2mjcf": [tool("body2mjcf"), loop, "-o", out("a.xml")],
            "body2gltf": [tool("body2gltf"), loop, "-o", out("a.gltf")],
            "bodysim": [tool("bodysim"), "check", loop],
            "bodyview": [tool("bodyview"), loop, "-o", out("a.html")],
            "bodydiff": [tool("bodydiff"), good, loop],
            "urdf2body": [tool("urdf2body"), urdf_loop, "-o", out("a.body")],
        }
        for what, argv in runs.items():
            run = subprocess.run(argv, capture_output=True, timeout=60)
            text = (run.stdout + run.stderr).decode("utf-8", "replace")
            if run.returncode != 2 or LOOP_TEXT not in text or "no such file" in text:
                failures.append(f"{what}: exit {run.returncode}:\n{text}")
            else:
                print(f"{what}: exit 2, {text.strip().splitlines()[0]}")

        main_body = os.path.join(folder, "main.body")
        with open(main_body, "w") as f:
            f.write(
                "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n"
                "  - {name: base, joint_type: free, mass: 1, inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1]}\n"
                "  - type: SubBody\n    uri: loop.body\n"
            )
        run = subprocess.run([tool("bodycheck"), main_body], capture_output=True, timeout=60)
        text = (run.stdout + run.stderr).decode("utf-8", "replace")
        if run.returncode == 0 or f"{main_body}:6:10:" not in text or LOOP_TEXT not in text:
            failures.append(f"SubBody naming a loop: exit {run.returncode}:\n{text}")
        else:
            print("SubBody naming a loop: reported at main.body:6:10")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
