#!/usr/bin/env python3
"""Every reference to a section of a Markdown file, written as `FILE.md, "SECTION"` (or
`FILE.md ("SECTION")`) in .pre-commit-hooks.yaml, README.md and the Markdown files under docs/
and converters/, names a file of the repository with a heading that
is SECTION or begins with it ("Two readings" for "Two readings: urdf2body and ..."). A hook's
comment that sends a user to a README section that does not exist (issue 47) fails.

usage: section_references.py REPO_ROOT   (registered in tests/CMakeLists.txt). The comment
lines of the YAML file are read joined, without their `#`, so a reference may break across them.
"""
import glob
import os
import re
import sys

REFERENCE = re.compile(r'([\w./-]+\.md),?\s+\(?"([^"]+)"')


def prose(path, text):
    if path.endswith(".md"):
        return re.sub(r"\s+", " ", text)
    comments = [re.sub(r"^\s*#\s?", "", line) for line in text.splitlines() if line.lstrip().startswith("#")]
    return " ".join(comments)


def headings(path):
    with open(path, encoding="utf-8") as f:
        return [m.group(1).strip() for m in re.finditer(r"^#+\s+(.*)$", f.read(), re.M)]


def main():
    root = sys.argv[1]
    files = [".pre-commit-hooks.yaml", "README.md"] + sorted(
        os.path.relpath(p, root) for folder in ("docs", "converters")
        for p in glob.glob(os.path.join(root, folder, "**", "*.md"), recursive=True))
    failures, checked = [], 0
    for name in files:
        with open(os.path.join(root, name), encoding="utf-8") as f:
            text = prose(name, f.read())
        for doc, section in REFERENCE.findall(text):
            checked += 1
            path = os.path.join(root, doc)
            if not os.path.isfile(path):
                failures.append(f"{name}: {doc} (section \"{section}\") is not a file of the repository")
                continue
            if not any(h == section or h.startswith(section + ":") or h.startswith(section + " ")
                       for h in headings(path)):
                failures.append(f"{name}: {doc} has no section \"{section}\"")
    for f in failures:
        print("FAIL: " + f)
    if checked < 3:
        print(f"FAIL: only {checked} section references in {len(files)} files (is the parsing broken?)")
        return 1
    print(f"{checked} section references checked in {len(files)} files" + (": FAIL" if failures else ": ok"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
