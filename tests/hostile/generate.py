#!/usr/bin/env python3
"""Writes the hostile inputs that are too large to keep in the repository into OUT_DIR:

- chain_100k.body, star_100k.body: 100,000 links, each the child of the one before / of the root;
- multi_megabyte_scalar.body: a 4 MB link name;
- list_1M_single_line.body: a 1,000,000-element flow list on one line;
- stl_over_triangle_limit.body (and big.stl): a binary STL of 1,000,001 triangles (50 MB), one over
  --max-mesh-triangles, which every tool refuses at its uri before importing it.

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


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
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
