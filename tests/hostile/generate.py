#!/usr/bin/env python3
"""Writes the hostile inputs that are too large to keep in the repository into OUT_DIR:

- chain_100k.body, star_100k.body: 100,000 links, each the child of the one before / of the root;
- multi_megabyte_scalar.body: a 4 MB link name;
- list_1M_single_line.body: a 1,000,000-element flow list on one line;
- stl_over_triangle_limit.body (and big.stl): a binary STL of 1,000,001 triangles (50 MB), one over
  --max-mesh-triangles, which every tool refuses at its uri before importing it;
- urdf_100k_one_line.urdf: a 100,000-link chain with every element on one line, and
  urdf_cycle_100k.urdf: a root and a cycle of 100,000 links, both of which urdf2body took
  quadratic time on (issue 34: 10,000 links on one line, 23.5 s).

    generate.py OUT_DIR
"""
import os
import struct
import sys

HEADER = "format: ChoreonoidBody\nformat_version: 2.0\nname: {name}\nlinks:\n"
ROOT = "  - {name: L0, joint_type: free, mass: 1, inertia: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1]}\n"
LINK = ("  - {{name: L{i}, parent: {parent}, joint_type: revolute, joint_id: {j}, joint_axis: Z, "
        "translation: [0.01, 0, 0], mass: 1, inertia: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1], "
        "elements: [{{type: Shape, geometry: {{type: Box, size: [0.01, 0.01, 0.01]}}}}]}}\n")


def tree(path, name, n, chain, expect):
    with open(path, "w") as f:
        f.write(expect)
        f.write(HEADER.format(name=name))
        f.write(ROOT)
        for i in range(1, n):
            f.write(LINK.format(i=i, parent=f"L{i - 1}" if chain else "L0", j=i - 1))


URDF_LINK = ('<link name="L{i}"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" '
             'izz="0.1"/></inertial><visual><geometry><box size="0.01 0.01 0.01"/></geometry></visual></link>')
URDF_JOINT = ('<joint name="J{i}" type="revolute"><parent link="L{parent}"/><child link="L{i}"/>'
              '<origin xyz="0.01 0 0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>')


def urdf_files(out):
    with open(os.path.join(out, "urdf_100k_one_line.urdf"), "w") as f:
        f.write("<!--\n# expect: urdf2body exit=0\n# limit: cpu=30\n-->\n<robot name=\"OneLine\">")
        for i in range(100_000):
            f.write(URDF_LINK.format(i=i))
            if i > 0:
                f.write(URDF_JOINT.format(i=i, parent=i - 1))
        f.write("</robot>\n")
    with open(os.path.join(out, "urdf_cycle_100k.urdf"), "w") as f:
        f.write("<!--\n# expect: urdf2body exit=2 rule=import-structure\n# limit: cpu=30\n-->\n<robot name=\"Cycle\">\n")
        f.write('<link name="root"/>\n')
        n = 100_000
        for i in range(n):
            f.write(URDF_LINK.format(i=i) + "\n")
        for i in range(n):
            f.write(URDF_JOINT.format(i=i, parent=(i - 1) % n) + "\n")
        f.write("</robot>\n")


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    urdf_files(out)
    clean = ("# expect: bodyinfo exit=0\n# expect: bodycheck exit=0\n# expect: body2urdf exit=0\n"
             "# expect: body2gltf exit=0\n# limit: cpu=20\n")
    tree(os.path.join(out, "chain_100k.body"), "Chain", 100_000, True, "# A 100,000-link chain.\n" + clean)
    tree(os.path.join(out, "star_100k.body"), "Star", 100_000, False, "# A 100,000-link star.\n" + clean)
    with open(os.path.join(out, "multi_megabyte_scalar.body"), "w") as f:
        f.write("# A 4 MB link name: it loads, and reports show a bounded excerpt of it.\n")
        f.write("# expect: bodyinfo exit=0\n# expect: bodycheck exit=0\n")
        f.write(HEADER.format(name="Big"))
        f.write('  - {name: "' + "N" * 4_000_000 + '", joint_type: free, mass: 1, inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1]}\n')
    with open(os.path.join(out, "list_1M_single_line.body"), "w") as f:
        f.write("# A 1,000,000-element list on one line, as an unknown key of a link.\n")
        f.write("# expect: bodyinfo exit=0\n# expect: bodycheck exit=0\n# expect: body2urdf exit=0\n")
        f.write(HEADER.format(name="List"))
        f.write("  - {name: A, joint_type: free, mass: 1, inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1], data: [")
        f.write(", ".join(["0"] * 1_000_000))
        f.write("]}\n")
    binary_stl_over_limit(out)


def binary_stl_over_limit(folder):
    os.makedirs(folder, exist_ok=True)
    n = 1_000_001
    triangle = struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 0.001, 0, 0, 0, 0.001, 0, 0)
    with open(os.path.join(folder, "big.stl"), "wb") as f:
        f.write(b"\0" * 80 + struct.pack("<I", n))
        f.write(triangle * n)
    with open(os.path.join(folder, "stl_over_triangle_limit.body"), "w") as f:
        f.write("# A binary STL one triangle over --max-mesh-triangles: refused at its uri, not imported.\n"
                "# expect: bodycheck exit=1 rule=mesh-too-large\n# expect: bodyinfo exit=1 rule=mesh-too-large\n")
        f.write(HEADER.format(name="BigMesh"))
        f.write("  - {name: B, joint_type: free, mass: 1, inertia: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1],\n"
                "     elements: [{type: Shape, geometry: {type: Resource, uri: big.stl}}]}\n")


if __name__ == "__main__":
    main()
