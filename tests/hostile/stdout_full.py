#!/usr/bin/env python3
"""A failed write of a tool's main output to standard output is exit 2 with a message (issue 34).

    stdout_full.py SOURCE_DIR BIN_DIR

Every tool (the folders of tools/ with a program in BIN_DIR) writes its main output to
/dev/full, where every write fails with ENOSPC: each must exit 2 and say it could not write
standard output. Tools with several outputs run each: bodydiff's pair, --textconv, --git,
--git-rev and --staged; bodycheck's text, JSON and SARIF reports; bodysim check; the exporters
with -o -; --help of each. A tool without a command here fails the test, so a new one cannot
be missed.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

MODEL = """format: ChoreonoidBody
format_version: 2.0
name: M
links:
  - name: ROOT
    joint_type: free
    mass: {mass}
    inertia: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1]
    elements:
      - type: Shape
        geometry: {{ type: Box, size: [0.2, 0.2, 0.2] }}
  - name: ARM
    parent: ROOT
    joint_type: revolute
    joint_id: 0
    joint_axis: Z
    mass: 0.5
    inertia: [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01]
"""
URDF = """<robot name="r"><link name="a"><inertial><mass value="1"/>
<inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link></robot>
"""


def git(work, *args):
    env = dict(os.environ, GIT_CONFIG_NOSYSTEM="1", HOME=work, GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@example.com",
               GIT_COMMITTER_NAME="t", GIT_COMMITTER_EMAIL="t@example.com")
    subprocess.run(["git", *args], cwd=work, env=env, check=True, capture_output=True)


def main():
    source, bin_dir = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as work:
        old, new, heavy, urdf = (os.path.join(work, n) for n in ("old.body", "new.body", "heavy.body", "r.urdf"))
        for path, text in ((old, MODEL.format(mass=1)), (new, MODEL.format(mass=2)), (heavy, MODEL.format(mass=2)),
                           (urdf, URDF)):
            with open(path, "w") as f:
                f.write(text)
        git(work, "init", "-q")
        git(work, "add", "old.body", "new.body")
        git(work, "commit", "-qm", "models")
        shutil.copy(old, new)  # differs from HEAD
        git(work, "add", "new.body")
        runs = {
            "keys_doc": [["keys_doc"]],
            "bodyinfo": [["bodyinfo", old], ["bodyinfo", "--format", "yaml", old]],
            "bodycheck": [["bodycheck", old], ["bodycheck", "--format", "json", old],
                          ["bodycheck", "--format", "sarif", old], ["bodycheck", "--list-rules"]],
            "bodydiff": [["bodydiff", old, heavy], ["bodydiff", "--textconv", old],
                         ["bodydiff", "--git", "heavy.body", old, "0" * 40, "100644", heavy, "1" * 40, "100644"],
                         ["bodydiff", "--git-rev", "HEAD", "new.body"], ["bodydiff", "--staged", "new.body"]],
            "bodysim": [["bodysim", "check", old]],
            "body2urdf": [["body2urdf", old, "-o", "-"]],
            "body2mjcf": [["body2mjcf", old, "-o", "-"]],
            "body2gltf": [["body2gltf", old, "-o", "-"]],
            "urdf2body": [["urdf2body", urdf, "-o", "-"]],
            "bodyview": [["bodyview", old, "-o", "-"]],
            "rules_doc": [["rules_doc"]],
            "bodyls": [["bodyls"]],  # an editor's initialize on standard input: the reply cannot be written
        }
        initialize = json.dumps({"jsonrpc": "2.0", "id": 1, "method": "initialize",
                                 "params": {"processId": None, "rootUri": None, "capabilities": {}}})
        stdin_of = {"bodyls": f"Content-Length: {len(initialize)}\r\n\r\n{initialize}"}
        tools = sorted(d for d in os.listdir(os.path.join(source, "tools"))
                       if os.path.isfile(os.path.join(source, "tools", d, "main.cpp"))
                       and os.access(os.path.join(bin_dir, d), os.X_OK))
        failures, count = [], 0
        for tool in tools:
            if tool not in runs:
                failures.append(f"{tool}: no command in stdout_full.py")
                continue
            commands = runs[tool] + ([[tool, "--help"]] if tool not in ("rules_doc", "keys_doc") else [])
            for argv in commands:
                count += 1
                with open("/dev/full", "w") as full:
                    run = subprocess.run([os.path.join(bin_dir, argv[0]), *argv[1:]], stdout=full,
                                         stderr=subprocess.PIPE, text=True, cwd=work, timeout=300,
                                         input=stdin_of.get(argv[0], "") if len(argv) == 1 else "")
                what = " ".join(argv).replace(work + "/", "")
                if run.returncode != 2 or "standard output" not in run.stderr:
                    failures.append(f"{what} > /dev/full: exit {run.returncode}, expected 2 and a message\n"
                                    f"{run.stderr[-500:]}")
    for f in failures:
        print("FAIL: " + f)
    print(f"stdout_full: {count} runs, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
