#!/usr/bin/env python3
"""Fails when a doctest TEST_CASE name holds a ';': ctest reads a discovered test's name as a
CMake list, so such a case is registered as two tests that both fail (it happened twice).
Before scanning the project it checks itself on a planted name, so it cannot pass by finding
nothing.

    test_case_names.py SOURCE_DIR
"""
import pathlib
import re
import sys

# TEST_CASE( then one or more adjacent string literals (the name, maybe split over lines).
CASE = re.compile(r'\bTEST_CASE(?:_FIXTURE)?\s*\(\s*((?:"(?:[^"\\]|\\.)*"\s*)+)', re.S)
LITERAL = re.compile(r'"((?:[^"\\]|\\.)*)"')


def bad_names(text):
    for match in CASE.finditer(text):
        name = "".join(LITERAL.findall(match.group(1)))
        if ";" in name:
            yield text.count("\n", 0, match.start()) + 1, name


def main():
    planted = 'TEST_CASE(\n    "a name split over lines, "\n    "with a; in its second half") {\n}\n'
    if [line for line, _ in bad_names(planted)] != [1]:
        sys.exit("test_case_names.py: the planted name with a ';' was not found")
    root = pathlib.Path(sys.argv[1])
    found, files = [], 0
    for path in sorted(root.glob("tests/**/*.cpp")):
        files += 1
        found += [(path, line, name) for line, name in bad_names(path.read_text(errors="replace"))]
    for path, line, name in found:
        print(f"{path.relative_to(root)}:{line}: a test case name with ';' (ctest splits it): {name}")
    print(f"{files} test sources checked")
    sys.exit(1 if found or not files else 0)


if __name__ == "__main__":
    main()
