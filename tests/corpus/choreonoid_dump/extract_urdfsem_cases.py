#!/usr/bin/env python3
"""Writes the small URDFs of tests/unit/converters/urdf/urdf_choreonoid_semantics_test.cpp as
files, each with its one-line wrapper body file, so that Choreonoid's URDF loader can be run on
them (choreonoid_dump) and its values kept as references (tests/data/urdf_choreonoid).

usage: extract_urdfsem_cases.py UNIT_TEST.cpp OUT_DIR
Writes OUT_DIR/NAME.urdf and OUT_DIR/NAME.body (`model_file: NAME.urdf`) for each URDF constant,
each refused comma form of case (e) and each mutant of the complete URDF (m01..m15, in the
order of the test's table); prints the mutants with the rule and place the unit test expects.
"""
import pathlib
import re
import sys

NAMES = {"kNoInertial": "a_no_inertial", "kWorld": "b_world", "kFixedAxes": "c_fixed_axes", "kBoxes": "d_boxes",
         "kCommas": "e_commas", "kComplete": "complete", "kLateMaterial": "late_material"}
# The unit test's refused comma forms of case (e): a doubled comma, a missing number, a fourth one.
REFUSED_XYZ = ["0,,1,2", "0, 1", "0, 1, 2, 3"]
# The mutants of kComplete, in the order of the test's table.
MUTANTS = ["zero_mass", "no_effort", "no_velocity", "negative_effort", "no_ixy", "empty_axis", "two_shapes",
           "capsule", "link_without_inertial", "inertial_without_inertia", "floating", "planar", "screw",
           "zero_length_cylinder", "negative_sphere"]
STRING = r'"((?:[^"\\]|\\.)*)"'


def c_strings(text):
    """The value of adjacent C string literals."""
    return "".join(re.findall(STRING, text)).encode().decode("unicode_escape")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    src = pathlib.Path(sys.argv[1]).read_text()
    out = pathlib.Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)

    def write(name, urdf):
        (out / f"{name}.urdf").write_text(urdf)
        (out / f"{name}.body").write_text(f"model_file: {name}.urdf\n")

    consts = dict(re.findall(r'const char\* const (k\w+) = R"\(\n(.*?)\)";', src, re.S))
    if set(consts) != set(NAMES):
        sys.exit(f"the test's URDF constants changed: {sorted(consts)}")
    for const, urdf in consts.items():
        write(NAMES[const], urdf)
    for i, xyz in enumerate(REFUSED_XYZ, 1):
        write(f"e_commas_refused_{i}", consts["kCommas"].replace("0.07, 0, -0.69", xyz, 1))
    table = src[src.index("const Mutant mutants[] = {"):]
    table = table[table.index("{") + 1:table.index("\n  };")]
    literal = rf'((?:{STRING}\s*)+)'
    entries = re.findall(rf'\{{{literal},\s*{literal},\s*"([\w-]+)",\s*\{{(\d+), (\d+)\}}\}}', table)
    if len(entries) != len(MUTANTS):
        sys.exit(f"the test has {len(entries)} mutants, this script names {len(MUTANTS)}")
    for i, entry in enumerate(entries):
        find, replace, rule, line, column = c_strings(entry[0]), c_strings(entry[2]), entry[4], entry[5], entry[6]
        if find not in consts["kComplete"]:
            sys.exit(f"mutant {i + 1}: {find!r} is not in kComplete")
        name = f"m{i + 1:02d}_{MUTANTS[i]}"
        write(name, consts["kComplete"].replace(find, replace, 1))
        print(f"{name}: the unit test expects {rule} at {line}:{column}")


if __name__ == "__main__":
    main()
