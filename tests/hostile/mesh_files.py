#!/usr/bin/env python3
"""Files a mesh names, and the size of a mesh (issue 45). What a repository cannot hold is made
here, at test time.

    mesh_files.py BIN_DIR SOURCE_DIR

1. An OBJ whose mtllib, and a glTF whose buffer, is a FIFO: every tool (run_case.py) answers
   with a located [mesh-file-unreadable] instead of blocking forever.
2. A glTF buffer over --max-file-size: refused with a located [mesh-file-unreadable]; within
   the limit the same model is clean.
3. Cubes of 0.1 µm, 1 µm and 1 m edge (tests/data/hostile/mesh_cube_1um): bodyinfo --mass-from-geometry
   and bodycheck --fix=geometry give the volume a³ and the inertia m a²/6 about the centre,
   computed by hand, within the float32 rounding of the OBJ's coordinates (1e-7 relative).
"""
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile

BIN, SOURCE = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
failures = []


def expect(what, ok, text=""):
    if not ok:
        failures.append(f"{what}\n{text[-2000:]}")


def run(argv, cwd):
    try:
        r = subprocess.run(argv, cwd=cwd, capture_output=True, timeout=60)
    except subprocess.TimeoutExpired:
        return None, f"{argv}: no answer within 60 s"
    return r.returncode, (r.stdout + r.stderr).decode("utf-8", "replace")


BODY = """{header}format: ChoreonoidBody
format_version: 2.0
name: M
links:
  - name: BASE
    joint_type: fixed
    mass: 1
    inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1]
    elements:
{elements}"""


def gltf(buffer, length):
    return json.dumps({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"uri": buffer, "byteLength": length}]})


def element(uri):
    return "      - {type: Shape, geometry: {type: Resource, uri: %s}}\n" % uri


def fifos(root):
    case = os.path.join(root, "fifo")
    os.makedirs(os.path.join(case, "meshes"))
    with open(os.path.join(case, "meshes", "fifo.obj"), "w") as f:
        f.write("mtllib fifo.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    with open(os.path.join(case, "meshes", "fifo.gltf"), "w") as f:
        f.write(gltf("fifo.bin", 36))
    os.mkfifo(os.path.join(case, "meshes", "fifo.mtl"))
    os.mkfifo(os.path.join(case, "meshes", "fifo.bin"))
    header = "".join("# expect: %s exit=%s rule=mesh-file-unreadable\n" % (tool, code)
                     for tool, code in (("bodyinfo", 1), ("bodycheck", 1), ("body2urdf", 2), ("body2mjcf", 2),
                                        ("body2gltf", 2)))
    with open(os.path.join(case, "main.body"), "w") as f:
        f.write(BODY.format(header=header, elements=element("meshes/fifo.obj") + element("meshes/fifo.gltf")))
    r = subprocess.run([sys.executable, os.path.join(SOURCE, "tests", "hostile", "run_case.py"), case, BIN],
                       capture_output=True, timeout=1200)
    expect("run_case.py on an OBJ mtllib and a glTF buffer that are FIFOs failed", r.returncode == 0,
           (r.stdout + r.stderr).decode("utf-8", "replace"))


def buffer_over_limit(root):
    case = os.path.join(root, "big")
    os.makedirs(case)
    with open(os.path.join(case, "big.bin"), "wb") as f:
        f.write(struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + bytes(2000 - 36))
    with open(os.path.join(case, "big.gltf"), "w") as f:
        f.write(gltf("big.bin", 2000))
    with open(os.path.join(case, "main.body"), "w") as f:
        f.write(BODY.format(header="", elements=element("big.gltf")))
    code, text = run([os.path.join(BIN, "bodycheck"), "--max-file-size", "1000", "main.body"], case)
    expect(f"a 2000-byte glTF buffer with --max-file-size 1000: exit {code}, expected 1", code == 1, text)
    expect("a buffer over --max-file-size: no located [mesh-file-unreadable] at the uri (line 10)",
           re.search(r"^main\.body:10:\d+: error: .*big\.bin.*\[mesh-file-unreadable\]$", text, re.M), text)
    code, text = run([os.path.join(BIN, "bodycheck"), "--max-file-size", "3000", "main.body"], case)
    expect(f"the same buffer within --max-file-size 3000: exit {code}, expected 0", code == 0, text)


def close(a, b, rel=1e-7):
    return abs(a - b) <= rel * abs(b)


def cubes(root):
    case = os.path.join(root, "cubes")
    shutil.copytree(os.path.join(SOURCE, "tests", "data", "hostile", "mesh_cube_1um"), case)
    code, text = run([os.path.join(BIN, "bodyinfo"), "--mass-from-geometry", "1000", "--format", "json", "main.body"],
                     case)
    expect(f"bodyinfo --mass-from-geometry: exit {code}", code == 0, text)
    if code != 0:
        return
    links = {link["name"]: link for link in json.loads(text)["links"]}
    for name, edge, mass in (("TINY", 1e-7, 1e-18), ("SMALL", 1e-6, 1e-15), ("LARGE", 1.0, 1000.0)):
        link = links[name]
        expect(f"{name}: volume {link['volume']}, expected {edge ** 3} (a³)", close(link["volume"], edge ** 3), text)
        inertia = link["computed_at_written_mass"]["inertia"]
        moment = mass * edge * edge / 6
        expect(f"{name}: inertia {inertia}, expected {moment} on the diagonal (m a²/6)",
               all(close(inertia[i], moment) for i in (0, 4, 8)) and all(abs(inertia[i]) <= 1e-7 * moment
                                                                        for i in (1, 2, 3, 5, 6, 7)), text)
    # --fix=geometry rewrites a flagged inertia with the shape's: the hand-computed one.
    path = os.path.join(case, "main.body")
    with open(path) as f:
        body = f.read()
    # A moving root, so that the inertia rules judge it (a welded one they leave alone).
    body = body.replace("[1.6666667e-28, 0, 0, 0, 1.6666667e-28, 0, 0, 0, 1.6666667e-28]", "[1, 0, 0, 0, 1, 0, 0, 0, 1]")
    body = body.replace("name: SMALL\n    joint_type: fixed", "name: SMALL\n    joint_type: free")
    with open(path, "w") as f:
        f.write(body)
    code, text = run([os.path.join(BIN, "bodycheck"), "--fix=geometry", "main.body"], case)
    with open(path) as f:
        fixed = f.read()
    found = re.search(r"name: SMALL\n(?:.*\n)*?\s+inertia: \[([^\]]*)\]", fixed)
    values = [float(v) for v in found.group(1).split(",")] if found else []
    expect(f"--fix=geometry on the 1 µm cube wrote inertia {values}, expected 1.6667e-28 on the diagonal",
           len(values) == 9 and all(close(values[i], 1e-15 * 1e-12 / 6, 1e-6) for i in (0, 4, 8)), text + fixed)


with tempfile.TemporaryDirectory() as root:
    fifos(root)
    buffer_over_limit(root)
    cubes(root)
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
