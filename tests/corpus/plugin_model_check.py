#!/usr/bin/env python3
"""A model Choreonoid refuses without a plugin must load here, with a warning per plugin type.

usage: plugin_model_check.py BODYINFO MODEL.body
Prints the closing count of links, joints and devices.
"""
import subprocess
import sys

tool, body = sys.argv[1:3]
run = subprocess.run([tool, body], capture_output=True, text=True, timeout=120)
plugin_warnings = [l for l in run.stderr.splitlines() if "[load-plugin-node]" in l]
print(run.stdout.splitlines()[0] if run.stdout else "(no output)")
for line in plugin_warnings:
    print(line)
if run.returncode != 0:
    print(f"bodyinfo exited {run.returncode}:\n{run.stderr}")
    sys.exit(1)
if not plugin_warnings:
    print("no load-plugin-node warning was reported")
    sys.exit(1)
