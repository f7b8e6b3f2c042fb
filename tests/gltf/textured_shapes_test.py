#!/usr/bin/env python3
"""body2gltf on our own model whose every tessellated geometry type carries a texture.

usage: textured_shapes_test.py BODY2GLTF NPM_PREFIX WORK_DIR

Writes a 4 x 4 PNG (made here with zlib, no image library) and a .body with a textured Box,
Sphere, Cylinder, Cone, Capsule, Extrusion, ElevationGrid, IndexedFaceSet (with and without texCoord) and
TriangleMesh, plus one untextured Box. Exports GLB and .gltf, then asserts:
  * body2gltf exits 0 and reports no export-loss (every texture is embedded);
  * the Khronos glTF validator (npm gltf-validator in NPM_PREFIX) finds 0 errors in both files;
  * the GLB holds one PNG image, every textured mesh has TEXCOORD_0 and a material with a
    baseColorTexture, the untextured box has neither, and each TEXCOORD_0 accessor's bounds are
    those of the mapping (u in [0, 1], except up to 1 + 1/n on a seam the division does not
    hit; v in [0, 1]).
The files stay in WORK_DIR for inspection.
"""
import json, os, pathlib, struct, subprocess, sys, zlib

def png(width, height, rgb_of):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    rows = b"".join(b"\x00" + b"".join(bytes(rgb_of(x, y)) for x in range(width)) for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))

TEXTURED = ["box", "sphere", "cylinder", "cone", "capsule", "extrusion", "grid", "faces", "faces_default", "triangles"]

BODY = """# Every tessellated geometry with a texture (tests/gltf/textured_shapes_test.py writes this).
format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
name: TexturedShapes
links:
  - name: BASE
    joint_type: fixed
    elements:
      - type: Shape
        name: box
        translation: [0, 0, 0]
        geometry: { type: Box, size: [0.2, 0.1, 0.3] }
        appearance: &tex { material: { diffuse: [1, 1, 1] }, texture: { uri: "grid.png" } }
      - type: Shape
        name: sphere
        translation: [0.3, 0, 0]
        geometry: { type: Sphere, radius: 0.1, division_number: 10 }
        appearance: *tex
      - type: Shape
        name: cylinder
        translation: [0.6, 0, 0]
        geometry: { type: Cylinder, radius: 0.1, height: 0.2 }
        appearance: *tex
      - type: Shape
        name: cone
        translation: [0.9, 0, 0]
        geometry: { type: Cone, radius: 0.1, height: 0.2 }
        appearance: *tex
      - type: Shape
        name: capsule
        translation: [1.2, 0, 0]
        geometry: { type: Capsule, radius: 0.05, height: 0.1 }
        appearance: *tex
      - type: Shape
        name: extrusion
        translation: [1.5, 0, 0]
        geometry: { type: Extrusion, cross_section: [0.05, 0.05, 0.05, -0.05, -0.05, -0.05, -0.05, 0.05, 0.05, 0.05],
                    spine: [0, 0, 0, 0, 0.1, 0, 0.05, 0.2, 0] }
        appearance: *tex
      - type: Shape
        name: grid
        translation: [0, 0.5, 0]
        geometry: { type: ElevationGrid, x_dimension: 3, z_dimension: 3, x_spacing: 0.1, z_spacing: 0.1,
                    height: [0, 0.01, 0, 0.01, 0.03, 0.01, 0, 0.01, 0] }
        appearance: *tex
      - type: Shape
        name: faces
        translation: [0.3, 0.5, 0]
        geometry:
          type: IndexedFaceSet
          vertices: [0, 0, 0, 0.2, 0, 0, 0.2, 0.1, 0, 0, 0.1, 0]
          faces: [0, 1, 2, 3, -1]
          tex_coords: [0, 0, 1, 0, 1, 1, 0, 1]
        appearance: *tex
      - type: Shape
        name: faces_default
        translation: [0.6, 0.5, 0]
        geometry:
          type: IndexedFaceSet
          vertices: [0, 0, 0, 0.2, 0, 0, 0.2, 0.1, 0, 0, 0.1, 0]
          faces: [0, 1, 2, 3, -1]
        appearance: *tex
      - type: Shape
        name: triangles
        translation: [0.9, 0.5, 0]
        geometry:
          type: TriangleMesh
          vertices: [0, 0, 0, 0.2, 0, 0, 0, 0.1, 0]
          faces: [0, 1, 2]
          tex_coords: [0, 0, 1, 0, 0, 1]
        appearance: *tex
      - type: Shape
        name: plain_box
        translation: [1.2, 0.5, 0]
        geometry: { type: Box, size: [0.1, 0.1, 0.1] }
        appearance: { material: { diffuse: [0.8, 0.2, 0.2] } }
"""

def glb_chunks(data):
    """(JSON document, BIN chunk bytes) of a GLB."""
    magic, version, length = struct.unpack_from("<III", data, 0)
    assert magic == 0x46546C67 and version == 2 and length == len(data), "not a GLB"
    chunk_length, chunk_type = struct.unpack_from("<II", data, 12)
    assert chunk_type == 0x4E4F534A
    doc = json.loads(data[20:20 + chunk_length])
    at = 20 + chunk_length
    bin_length, bin_type = struct.unpack_from("<II", data, at)
    assert bin_type == 0x004E4942
    return doc, data[at + 8:at + 8 + bin_length]

def floats(doc, binary, accessor, width):
    """The float vectors of an accessor (tightly packed or strided)."""
    acc = doc["accessors"][accessor]
    view = doc["bufferViews"][acc["bufferView"]]
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    stride = view.get("byteStride", 4 * width)
    return [struct.unpack_from(f"<{width}f", binary, start + i * stride) for i in range(acc["count"])]

def main():
    tool, npm, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    modules = npm / "node_modules"
    if not (modules / "gltf-validator").is_dir():
        print(f"gltf-validator is not installed in {npm} (README command 2 installs it)")
        return 1
    work.mkdir(parents=True, exist_ok=True)
    (work / "grid.png").write_bytes(png(4, 4, lambda x, y: (255, 255, 255) if (x + y) % 2 else (30, 60, 200)))
    model = work / "textured_shapes.body"
    model.write_text(BODY)
    failures = []
    outputs = []
    for name in ("textured_shapes.glb", "gltf/textured_shapes.gltf"):
        out = work / name
        out.parent.mkdir(exist_ok=True)
        p = subprocess.run([tool, str(model), "-o", str(out)], capture_output=True, text=True)
        print(f"body2gltf -o {name}: exit {p.returncode}")
        if p.returncode != 0 or "export-loss" in p.stderr:
            failures.append(f"{name}: exit {p.returncode}: {p.stderr.strip()[-500:]}")
        outputs.append(out)
    p = subprocess.run(["node", str(pathlib.Path(__file__).with_name("validate_gltf.js")), *map(str, outputs)],
                       capture_output=True, text=True, env={**os.environ, "NODE_PATH": str(modules)})
    print(p.stdout.strip())
    for out in outputs:
        line = next((l for l in p.stdout.splitlines() if l.startswith(str(out) + " ")), "")
        if " errors=0 " not in line:
            failures.append(f"validator: {line or p.stderr.strip()[-300:]}")

    doc, binary = glb_chunks((work / "textured_shapes.glb").read_bytes())
    images = doc.get("images", [])
    if len(images) != 1 or images[0].get("mimeType") != "image/png" or "bufferView" not in images[0]:
        failures.append(f"expected one embedded PNG image, got {images}")
    mesh_of = {n["name"]: n["mesh"] for n in doc["nodes"] if "mesh" in n}
    for name in TEXTURED + ["plain_box"]:
        if name not in mesh_of:
            failures.append(f"no mesh node named {name}")
            continue
        prim = doc["meshes"][mesh_of[name]]["primitives"][0]
        material = doc["materials"][prim["material"]]
        has_uv = "TEXCOORD_0" in prim["attributes"]
        has_tex = "baseColorTexture" in material["pbrMetallicRoughness"]
        if name == "plain_box":
            if has_uv or has_tex:
                failures.append("the untextured box has texture coordinates or a texture")
            continue
        if not (has_uv and has_tex):
            failures.append(f"{name}: TEXCOORD_0 {has_uv}, baseColorTexture {has_tex}")
            continue
        acc = doc["accessors"][prim["attributes"]["TEXCOORD_0"]]
        lo, hi = acc["min"], acc["max"]
        # glTF puts the image origin top left, VRML bottom left: v_glTF = 1 - v.
        # The sphere has 10 divisions: ring vertex j has u = (7.5 - j) / 10 (mod 1), so no vertex
        # sits on the seam at -Z; u runs from 0.05 (j = 7) to 1.05 (j = 8's 0.95 neighbour
        # unwrapped across the seam).
        u_lo, u_hi = (0.05, 1.05) if name == "sphere" else (0.0, 1.0)
        # VRML97 default on a 0.2 x 0.1 quad: u = x / 0.2 in 0..1, v = y / 0.2 in 0..0.5,
        # so v_glTF in 0.5..1.
        v_lo = 0.5 if name == "faces_default" else 0.0
        ok = (abs(lo[0] - u_lo) < 1e-6 and abs(hi[0] - u_hi) < 1e-6 and abs(lo[1] - v_lo) < 1e-6
              and abs(hi[1] - 1) < 1e-6)
        print(f"{name}: TEXCOORD_0 min {lo} max {hi} {'ok' if ok else 'WRONG'}")
        if not ok:
            failures.append(f"{name}: TEXCOORD_0 bounds {lo} {hi}")
    # Vertex by vertex on the quad with its own tex_coords: corner (x, y) of the 0.2 x 0.1 quad
    # has (u, v) = (x / 0.2, y / 0.1) in the file, so (x / 0.2, 1 - y / 0.1) in glTF.
    if "faces" in mesh_of:
        prim = doc["meshes"][mesh_of["faces"]]["primitives"][0]
        points = floats(doc, binary, prim["attributes"]["POSITION"], 3)
        uvs = floats(doc, binary, prim["attributes"]["TEXCOORD_0"], 2)
        for (x, y, _), (u, v) in zip(points, uvs):
            if abs(u - x / 0.2) > 1e-6 or abs(v - (1 - y / 0.1)) > 1e-6:
                failures.append(f"faces: vertex ({x}, {y}) has ({u}, {v})")
        print(f"faces: {len(points)} vertices checked against (x / 0.2, 1 - y / 0.1)")
    for f in failures:
        print("FAIL:", f)
    print(f"textured shapes: {len(TEXTURED)} textured meshes, {len(failures)} failures")
    return 1 if failures else 0

if __name__ == "__main__":
    sys.exit(main())
