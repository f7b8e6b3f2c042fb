#!/usr/bin/env python3
"""Reports quote only files read as model text (issue 45, item 1).

    quoted_files.py BIN_DIR

A model may name any file: a SubBody's `uri`, a wrapper's `model_file`, a YAML resource. When
that file is no model (a credentials file, say), a finding located in it must not print its
lines: not in bodycheck's text, JSON or SARIF, not in bodyinfo's or an exporter's messages, not
in bodyview's HTML page. The finding is still reported, and so is the one at the line that
names the file. A control model whose included file is a real model with a finding must still
quote that file's line (so the test fails if quoting were simply switched off).
"""
import os
import re
import subprocess
import sys
import tempfile

SECRET = "root:$6$SECRET-45-HASH$xyz:19000:0:99999:7:::"
SECRET_MAPPING = "api_key: SECRET-45-KEY"

BOX_LINK = """  - name: base
    joint_type: free
    mass: 1
    inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1]
"""

# name -> (files, the model file, the line of the model file that names the secret file)
CASES = {
    "wrapper_yaml": ({"secret.yaml": SECRET + "\n"}, "model_file: secret.yaml\n", 1),
    "wrapper_body_mapping": ({"secret.body": SECRET_MAPPING + "\n"}, "model_file: secret.body\n", 1),
    "wrapper_urdf": ({"secret.urdf": SECRET + "\n"}, "model_file: secret.urdf\n", 1),
    "subbody": (
        {"secret": SECRET + "\n"},
        "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n" + BOX_LINK + "  - type: SubBody\n    uri: secret\n",
        9,
    ),
    "subbody_mapping": (
        {"secret.body": SECRET_MAPPING + "\n"},
        "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n" + BOX_LINK + "  - type: SubBody\n    uri: secret.body\n",
        9,
    ),
    "yaml_resource": (
        {"secret.yaml": SECRET + "\n"},
        "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n"
        + BOX_LINK
        + "    elements:\n      - type: Resource\n        uri: secret.yaml\n",
        10,
    ),
}

# A real sub-body with an unknown key: its line is quoted.
CONTROL_SUB = (
    "format: ChoreonoidBody\nformat_version: 2.0\nQUOTED_45_KEY: 1\nlinks:\n"
    "  - {name: sub, joint_type: free, mass: 1, inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1]}\n"
)
CONTROL = "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n" + BOX_LINK + "  - type: SubBody\n    uri: sub.body\n"


def outputs(bin_dir, folder, model):
    """Every text the tools print or write about `model`: {what: text}."""
    tool = lambda t: os.path.join(bin_dir, t)
    out = {}
    runs = {
        "bodycheck text": [tool("bodycheck"), model],
        "bodycheck json": [tool("bodycheck"), "--format", "json", model],
        "bodycheck sarif": [tool("bodycheck"), "--format", "sarif", model],
        "bodyinfo": [tool("bodyinfo"), model],
        "body2urdf": [tool("body2urdf"), model, "-o", os.path.join(folder, "out.urdf")],
    }
    page = os.path.join(folder, "page.html")
    runs["bodyview"] = [tool("bodyview"), model, "-o", page]
    for what, argv in runs.items():
        run = subprocess.run(argv, capture_output=True, timeout=120)
        out[what] = (run.stdout + run.stderr).decode("utf-8", "replace")
    if os.path.exists(page):
        out["bodyview page"] = open(page, encoding="utf-8", errors="replace").read()
        os.remove(page)
    return out


def main():
    bin_dir = sys.argv[1]
    failures = []
    with tempfile.TemporaryDirectory() as root:
        for name, (files, text, line) in CASES.items():
            folder = os.path.join(root, name)
            os.mkdir(folder)
            for file, content in files.items():
                with open(os.path.join(folder, file), "w") as f:
                    f.write(content)
            model = os.path.join(folder, "main.body")
            with open(model, "w") as f:
                f.write(text)
            got = outputs(bin_dir, folder, model)
            for what, output in got.items():
                for secret in ("SECRET-45-HASH", "SECRET-45-KEY"):
                    if secret in output:
                        failures.append(f"{name}: {what} prints a line of the file the model names ({secret})")
            # Still reported: an error at the line that names the file.
            at_line = re.compile(re.escape(model) + f":{line}:\\d+: (error|fatal error): ")
            if not at_line.search(got["bodycheck text"]):
                failures.append(f"{name}: bodycheck reports no error at main.body:{line}:\n{got['bodycheck text']}")
            print(f"{name}: {len(got)} outputs checked, error at main.body:{line}")

        folder = os.path.join(root, "control")
        os.mkdir(folder)
        with open(os.path.join(folder, "sub.body"), "w") as f:
            f.write(CONTROL_SUB)
        model = os.path.join(folder, "main.body")
        with open(model, "w") as f:
            f.write(CONTROL)
        got = outputs(bin_dir, folder, model)
        if "QUOTED_45_KEY: 1\n" not in got["bodycheck text"]:
            failures.append(f"control: a real sub-body's line is not quoted:\n{got['bodycheck text']}")
        else:
            print("control: a real sub-body's line is quoted")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
