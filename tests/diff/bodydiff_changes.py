#!/usr/bin/env python3
"""Every real change is reported, once, at its lines: a table of single edits on corpus models.

usage: bodydiff_changes.py BODYDIFF CORPUS_DIR WORK_DIR

Each row edits one line of a corpus model (in a copy) and states what bodydiff must report:
exactly one change that is not derived, of the stated kind, link and field, located in the new
file at the stated line and (for a change) in the old file at the stated old line. Derived
effects the row names (total mass, world frames) must be there too. Rows marked `same` are
valid variants: exit 0 and no output. The lines are those of the corpus files as written,
read off by hand.
"""
import json
import os
import re
import shutil
import subprocess
import sys

# (model, link whose block holds the edit (None: whole file), old line text, new line text,
#  expected: (kind, link, field, new line, old line) or "same", derived fields expected)
ROWS = [
    ("SR1/SR1.body", "WAIST_P", "    joint_range: [ -90, 90 ]", "    joint_range: [ -80, 90 ]",
     ("changed", "WAIST_P", "joint_range", 52, 52), []),
    ("SR1/SR1.body", "WAIST_P", "    joint_axis: [ 0, 1, 0 ]", "    joint_axis: [ 1, 0, 0 ]",
     ("changed", "WAIST_P", "joint_axis", 50, 50), []),
    ("SR1/SR1.body", "WAIST_P", "    joint_type: revolute", "    joint_type: prismatic",
     # A range is read in degrees for a revolute joint and in metres for a prismatic one.
     [("changed", "WAIST_P", "joint_type", 49, 49), ("changed", "WAIST_P", "joint_range", 52, 52)], []),
    ("SR1/SR1.body", "WAIST_P", "    joint_id: 26", "    joint_id: 40",
     ("changed", "WAIST_P", "joint_id", 51, 51), []),
    ("SR1/SR1.body", "WAIST_P", "    mass: 6.0", "    mass: 8.5",
     ("changed", "WAIST_P", "mass", 54, 54), ["total_mass", "center_of_mass"]),
    ("SR1/SR1.body", "WAIST_P", "    center_of_mass: [ 0, 0, -0.1 ]", "    center_of_mass: [ 0, 0, -0.2 ]",
     ("changed", "WAIST_P", "center_of_mass", 53, 53), ["center_of_mass"]),
    ("SR1/SR1.body", "WAIST_P", "      1, 0, 0,", "      2, 0, 0,",
     ("changed", "WAIST_P", "inertia", 55, 55), []),
    ("SR1/SR1.body", "WAIST_P", "    translation : [ 0, 0, 0.176 ]", "    translation : [ 0, 0, 0.2 ]",
     ("changed", "WAIST_P", "translation", 48, 48), ["world_frame"]),
    ("PA10/PA10.body", "J1", "    rotation: [ 0, 0, 1, 0 ]", "    rotation: [ 0, 0, 1, 30 ]",
     ("changed", "J1", "rotation", 33, 33), ["world_frame"]),
    ("SR1/SR1.body", "LARM_SHOULDER_P", "    parent: CHEST", "    parent: WAIST_R",
     ("changed", "LARM_SHOULDER_P", "parent", 168, 168), ["world_frame"]),
    ("SR1/SR1.body", "LARM_WRIST_R", "    joint_id:  25", "    joint_id:  25\n    max_joint_velocity: 2",
     # unlimited before; the old side has no key, so it points at the link
     ("changed", "LARM_WRIST_R", "joint_velocity_range", 306, 301), []),
    ("SR1/SR1.body", "LARM_WRIST_R", "    joint_id:  25", "    joint_id:  25\n    max_joint_effort: 30",
     # effort limits keep no location of their own: the link's
     ("changed", "LARM_WRIST_R", "joint_effort_range", 301, 301), []),
    ("SR1/SR1.body", "WAIST_R", "            geometry: { type: Box, size: [ 0.05, 0.05, 0.275 ] }",
     "            geometry: { type: Box, size: [ 0.05, 0.05, 0.3 ] }",
     # the box (visual and collision) is centred at z 0.1625: its top goes from 0.1625 + 0.275/2
     # to 0.1625 + 0.3/2; the other shape, a cylinder r 0.025 h 0.05 turned 90 deg about z,
     # keeps the rest of the box at 0.025. Located at the link, like the world frame.
     ("changed", "WAIST_R", "shape 1 size", 94, 94),
     [("visual_bounding_box", "min [-0.025, -0.025, -0.025] max [0.025, 0.025, 0.3]",
       "min [-0.025, -0.025, -0.025] max [0.025, 0.025, 0.3125]", 66),
      ("collision_bounding_box", "min [-0.025, -0.025, -0.025] max [0.025, 0.025, 0.3]",
       "min [-0.025, -0.025, -0.025] max [0.025, 0.025, 0.3125]", 66)]),
    ("SR1/SR1.body", "WAIST_P", "        geometry: { type: Cylinder, radius: 0.025, height: 0.05 }",
     "        geometry: { type: Sphere, radius: 0.025 }",
     ("changed", "WAIST_P", "shape 0 geometry", 61, 61), []),
    ("SR1/SR1.body", "WAIST_R", "        translation: [ 0, 0, 0.1625 ]", "        translation: [ 0, 0, 0.2 ]",
     # shapes keep one location (their first key): a placement or material change points there
     ("changed", "WAIST_R", "shape 1 placement", 94, 94),
     [("visual_bounding_box", None, "min [-0.025, -0.025, -0.025] max [0.025, 0.025, 0.3375]", 66),
      ("collision_bounding_box", None, "min [-0.025, -0.025, -0.025] max [0.025, 0.025, 0.3375]", 66)]),
    ("SR1/SR1.body", "WAIST_P", "            diffuse: [ 0.6, 1.0, 0.6 ]", "            diffuse: [ 0.5, 1.0, 0.6 ]",
     ("changed", "WAIST_P", "shape 0 material diffuse_color", 61, 61), []),
    ("SR1/SR1.body", "CHEST", "        near_clip_distance: 0.1", "        near_clip_distance: 0.2",
     ("changed", "CHEST", "device 'LeftCamera' near_clip_distance", 148, 148), []),
    ("SR1/SR1.body", "CHEST", "        translation: [ 0.15, 0.05, 0.15 ]", "        translation: [ 0.15, 0.06, 0.15 ]",
     # the camera's own shape (its `elements`) moves with it
     [("changed", "CHEST", "shape 4 placement", 154, 154), ("changed", "CHEST", "device 'LeftCamera' placement", 142, 142)],
     []),
    ("misc/ClosedLinkSample.body", "@extraJoints:", "    jointAxis: [ 0, 0, 1 ]", "    jointAxis: [ 0, 1, 0 ]",
     # an extra joint keeps one location (its first key)
     ("changed", "", "extra_joint 0 axis", 138, 138), []),
    # A link added before WAIST_P (lines after it move by 3, which is no change), and removed.
    ("SR1/SR1.body", "WAIST_P", "    name: WAIST_P",
     "    name: EXTRA\n    parent: WAIST\n    joint_type: fixed\n  -\n    name: WAIST_P",
     ("added", "EXTRA", "link", 46, None), ["total_mass", "center_of_mass"]),
    ("SR1/SR1.body", "WAIST_P", "    name: WAIST_P",
     "    name: EXTRA\n    parent: WAIST\n    joint_type: fixed\n  -\n    name: WAIST_P",
     ("removed", "EXTRA", "link", None, 46), ["total_mass", "center_of_mass"], "swap"),
    # Mesh files by content: the same bytes under another name are no change; other bytes are.
    ("PA10/PA10.body", None, '      Visual: { resource: { uri: "parts/BASE.wrl" } }',
     '      Visual: { resource: { uri: "parts/BASE_COPY.wrl" } }', "same", []),
    ("PA10/PA10.body", None, '      Visual: { resource: { uri: "parts/BASE.wrl" } }',
     '      Visual: { resource: { uri: "parts/BASE_EDITED.wrl" } }',
     # BASE's shape 0 is its Collision box; the Visual resource is shape 1
     # (0, 0, 0.5) in the file, turned 90 deg about x by the file's Transform: y = -0.5
     ("changed", "BASE", "shape 1 mesh", 17, 17), [("visual_bounding_box", None, "-0.5, ", 8)]),
    # Tracks: a pseudo continuous track's drive axis; a plugin track device's parameter (AGX),
    # and the same parameter respelled (camelCase or snake_case) and rewritten (1e-2 for 0.01).
    ("Tank/Tank.body", "TRACK_L", "    jointAxis: Y", "    jointAxis: Z",
     ("changed", "TRACK_L", "joint_axis", 18, 18), []),
    ("Tank/AgxTank.body", "TRACK_L", "        numberOfNodes: 42", "        numberOfNodes: 44",
     ("changed", "TRACK_L", "device 'TRACK_L' number_of_nodes", 32, 32), []),
    ("Tank/AgxTank.body", "TRACK_L", "        nodeThickness: 0.01", "        node_thickness: 1.0e-2", "same", []),
    # Textures by content, like meshes.
    ("house/cassette.body", None, '            url: "textures/tape1.front.png"',
     '            url: "textures/TATAMI.png"', ("changed", "WAIST", "shape 0 texture", 19, 19), []),
    ("house/cassette.body", None, '            url: "textures/tape1.front.png"',
     '            url: "textures/tape1_copy.png"', "same", []),
    # A link's contact material (kept with no location of its own: the link's)
    ("SR1/SR1.body", "LLEG_ANKLE_R", "    material: Sole", "    material: Ground",
     ("changed", "LLEG_ANKLE_R", "material", 555, 555), []),
    # A whole shape added (inside the chest's box: no bounding box change), and a whole device
    # added and removed.
    ("SR1/SR1.body", "CHEST", "        type: Shape",
     "        type: Shape\n        geometry: { type: Sphere, radius: 0.01 }\n        appearance: *Appearance3\n"
     "      -\n        type: Shape",
     ("added", "CHEST", "shape 6", 120, None), []),
    ("SR1/SR1.body", "CHEST", "        type: Camera",
     "        type: RateGyroSensor\n        name: GYRO2\n        id: 9\n      -\n        type: Camera",
     ("added", "CHEST", "device 'GYRO2'", 142, None), []),
    ("SR1/SR1.body", "CHEST", "        type: Camera",
     "        type: RateGyroSensor\n        name: GYRO2\n        id: 9\n      -\n        type: Camera",
     ("removed", "CHEST", "device 'GYRO2'", None, 142), [], "swap"),
]


def same_numbers(shown, expected):
    """The same words and numbers within 1e-12 (shown values are the shortest round trip)."""
    a, b = re.split(r"([-+0-9.e]+)", shown), re.split(r"([-+0-9.e]+)", expected)
    if len(a) != len(b):
        return False
    for i, (x, y) in enumerate(zip(a, b)):
        if i % 2 and abs(float(x) - float(y)) > 1e-12 or not i % 2 and x != y:
            return False
    return True


def edit(text, link, old, new):
    lines = text.split("\n")
    start = 0
    if link:
        marker = link[1:] if link.startswith("@") else f"name: {link}"
        start = next(i for i, l in enumerate(lines) if l.strip() == marker)
    i = next(i for i in range(start, len(lines)) if lines[i] == old)
    lines[i] = new
    return "\n".join(lines)


def main():
    bodydiff, corpus, work = sys.argv[1:4]
    if os.path.isdir(os.path.join(corpus, "choreonoid")):  # the shared corpus: models and references
        corpus = os.path.join(corpus, "choreonoid")
    shutil.rmtree(work, ignore_errors=True)
    shutil.copytree(corpus, work, ignore=shutil.ignore_patterns("reference"))
    parts = os.path.join(work, "PA10", "parts")
    shutil.copyfile(os.path.join(parts, "BASE.wrl"), os.path.join(parts, "BASE_COPY.wrl"))
    base = open(os.path.join(parts, "BASE.wrl"), encoding="latin-1").read()
    edited = base.replace("point\t[", "point\t[ 0 0 0.5,", 1)
    assert edited != base
    open(os.path.join(parts, "BASE_EDITED.wrl"), "w", encoding="latin-1").write(edited)
    textures = os.path.join(work, "house", "textures")
    shutil.copyfile(os.path.join(textures, "tape1.front.png"), os.path.join(textures, "tape1_copy.png"))

    failures = []
    for n, (model, link, old, new, expected, derived, *swap) in enumerate(ROWS):
        path = os.path.join(work, model)
        text = open(path, encoding="utf-8").read()
        changed = os.path.join(os.path.dirname(path), f"__change{n}_{os.path.basename(path)}")
        open(changed, "w", encoding="utf-8").write(edit(text, link, old, new))
        if swap:  # the edited file is the old one
            path, changed = changed, path
        r = subprocess.run([bodydiff, "--format", "json", path, changed], capture_output=True, text=True)
        what = f"row {n} ({model}: {new.strip()!r})"
        if expected == "same":
            t = subprocess.run([bodydiff, path, changed], capture_output=True, text=True)
            if r.returncode != 0 or t.returncode != 0 or t.stdout or t.stderr:
                failures.append(f"{what}: expected no change, exit {t.returncode}: {t.stdout}{t.stderr}")
            continue
        if r.returncode != 1:
            failures.append(f"{what}: exit {r.returncode}, not 1: {r.stderr}")
            continue
        changes = json.loads(r.stdout)["changes"]
        own = [c for c in changes if not c["derived"]]
        expected = expected if isinstance(expected, list) else [expected]
        got = sorted((c["kind"], c["link"] or "", c["field"], c["new"]["line"] if c["new"] else None,
                      c["old"]["line"] if c["old"] else None) for c in own)
        if got != sorted(expected):
            failures.append(f"{what}: got {got}, expected {expected}")
            continue
        for c in own:
            if c["new"] and c["new"]["file"] != changed or c["old"] and c["old"]["file"] != path:
                failures.append(f"{what}: files {c['old'] and c['old']['file']} -> {c['new'] and c['new']['file']}")
            if c["kind"] == "changed" and c["old"]["value"] == c["new"]["value"]:
                failures.append(f"{what}: old and new value shown alike: {c['old']['value']}")
        for d in derived:
            # a field name (reported at least once), or (field, old value or None, new value or a
            # part of it, line on both sides): reported exactly once with these values
            if not isinstance(d, tuple):
                if not any(x["derived"] and x["field"] == d for x in changes):
                    failures.append(f"{what}: derived {d} not reported")
                continue
            field, old_value, new_value, line = d
            found = [x for x in changes if x["derived"] and x["field"] == field]
            if len(found) != 1:
                failures.append(f"{what}: derived {field} reported {len(found)} times")
                continue
            x = found[0]
            if old_value is not None and not same_numbers(x["old"]["value"], old_value):
                failures.append(f"{what}: derived {field} was {x['old']['value']}, expected {old_value}")
            if new_value is not None and not (same_numbers(x["new"]["value"], new_value) if new_value.startswith("min")
                                              else new_value in x["new"]["value"]):
                failures.append(f"{what}: derived {field} is {x['new']['value']}, expected {new_value}")
            if (x["old"]["line"], x["new"]["line"]) != (line, line):
                failures.append(f"{what}: derived {field} at lines {x['old']['line']}/{x['new']['line']}, not {line}")
        if derived and all(isinstance(d, tuple) for d in derived):
            extra = sorted({x["field"] for x in changes if x["derived"]} - {d[0] for d in derived})
            if extra:
                failures.append(f"{what}: unexpected derived changes {extra}")
        if not derived and any(x["derived"] for x in changes):
            failures.append(f"{what}: unexpected derived changes {[x['field'] for x in changes if x['derived']]}")
    print(f"{len(ROWS)} rows, {len(failures)} failures")
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
