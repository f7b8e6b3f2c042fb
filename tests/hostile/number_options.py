#!/usr/bin/env python3
"""Every numeric option of every tool refuses a number that is not finite (issue 34).

    number_options.py SOURCE_DIR BIN_DIR

The tools are the folders of tools/ with a program of that name in BIN_DIR (and bodysim's
subcommands, from its --help); their numeric options are read from each --help (the type
FLOAT, INT, UINT or NUMBER), so that a new option or tool is tested without a change here.
Each gets nan, inf, -inf and 1e999: a usage error (exit 2) that names the option, never a run
(bodysim --accuracy nan used to abort in Simbody) and never a crash.
"""
import os
import re
import subprocess
import sys
import tempfile

NUMERIC = re.compile(r"^\s+(?:-\w,)?(--[\w-]+) (?:FLOAT|INT|UINT|NUMBER)\b", re.M)
VALUES = ["nan", "NaN", "inf", "-inf", "1e999"]


def help_text(argv):
    return subprocess.run(argv + ["--help"], capture_output=True, text=True, timeout=60).stdout


def main():
    source, bin_dir = sys.argv[1], sys.argv[2]
    tools = sorted(d for d in os.listdir(os.path.join(source, "tools"))
                   if os.path.isfile(os.path.join(source, "tools", d, "main.cpp"))
                   and os.access(os.path.join(bin_dir, d), os.X_OK)
                   and d not in ("rules_doc", "keys_doc"))  # the doc printers: no options
    failures, tested = [], 0
    with tempfile.TemporaryDirectory() as work:
        model = os.path.join(work, "m.body")
        with open(model, "w") as f:
            f.write("format: ChoreonoidBody\nformat_version: 2.0\nname: M\nlinks:\n  - name: ROOT\n"
                    "    joint_type: free\n    mass: 1\n    inertia: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1]\n")
        commands = []
        for tool in tools:
            program = os.path.join(bin_dir, tool)
            text = help_text([program])
            subcommands = re.findall(r"^\s+([a-z][\w-]*)\s", text.split("Subcommands:", 1)[1], re.M) \
                if "Subcommands:" in text else []
            for sub in subcommands or [None]:
                commands.append([program] + ([sub] if sub else []))
        if len(commands) < 10:
            failures.append(f"only {len(commands)} tools and subcommands found: {commands}")
        for command in commands:
            options = NUMERIC.findall(help_text(command))
            name = " ".join(os.path.basename(command[0]) if i == 0 else a for i, a in enumerate(command))
            if not options and not name.startswith(("rules_doc", "keys_doc")):
                failures.append(f"{name}: no numeric option in --help (every tool has the front's limits)")
            # The required options of the tools that have them, so that the number is the only fault.
            required = {"run": ["--scenario", model, "--csv", os.path.join(work, "out.csv")]}.get(command[-1], [])
            if re.search(r"^\s+-o,--output \S+ REQUIRED", help_text(command), re.M):
                required = ["-o", os.path.join(work, "out")]
            for option in options:
                for value in VALUES:
                    argv = command + [option, value] + required + [model]
                    tested += 1
                    try:
                        run = subprocess.run(argv, capture_output=True, text=True, timeout=60)
                    except subprocess.TimeoutExpired:
                        failures.append(f"{name} {option} {value}: no answer in 60 s")
                        continue
                    if run.returncode != 2 or option not in run.stderr:
                        failures.append(f"{name} {option} {value}: exit {run.returncode}, expected 2 with a usage "
                                        f"error naming {option}\n{run.stderr[-600:]}")
    for f in failures:
        print("FAIL: " + f)
    print(f"number_options: {len(commands)} commands, {tested} runs, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
