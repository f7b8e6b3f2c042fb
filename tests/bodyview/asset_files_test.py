#!/usr/bin/env python3
"""bodyview reads its viewer files through the bounded reader (issue 35): an installed asset
folder in which viewer.css is a FIFO (or too large, or missing) ends the run with exit 2 and a
message naming the file, within seconds, instead of blocking on the FIFO.

usage: asset_files_test.py BODYVIEW ASSETS_BUILD_DIR ASSETS_FROM_BINDIR MODEL WORK_DIR"""
import os
import shutil
import subprocess
import sys

bodyview, built_assets, from_bindir, model, work = sys.argv[1:6]
shutil.rmtree(work, ignore_errors=True)
failures = []


def run_case(name, spoil):
    root = os.path.join(work, name)
    bin_dir = os.path.join(root, "bin")
    os.makedirs(bin_dir)
    shutil.copy2(bodyview, os.path.join(bin_dir, "bodyview"))
    assets = os.path.normpath(os.path.join(bin_dir, from_bindir))
    shutil.copytree(built_assets, assets)
    spoil(os.path.join(assets, "viewer.css"))
    out = os.path.join(root, "page.html")
    try:
        run = subprocess.run([os.path.join(bin_dir, "bodyview"), "-q", model, "-o", out],
                             capture_output=True, text=True, timeout=60)
    except subprocess.TimeoutExpired:
        failures.append(f"{name}: bodyview did not end within 60 s")
        return
    if run.returncode != 2 or "viewer.css" not in run.stderr or os.path.exists(out):
        failures.append(f"{name}: exit {run.returncode}, page written: {os.path.exists(out)}, "
                        f"stderr: {run.stderr[-500:]}")
    else:
        print(f"{name}: {run.stderr.strip().splitlines()[-1]}")


def fifo(path):
    os.remove(path)
    os.mkfifo(path)


def folder(path):
    os.remove(path)
    os.mkdir(path)


def unreadable_size(path):
    with open(path, "wb") as f:  # sparse: 65 MiB that take no disk
        f.truncate(65 << 20)


run_case("fifo", fifo)
run_case("folder", folder)
run_case("too_large", unreadable_size)
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
