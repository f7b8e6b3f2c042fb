#!/usr/bin/env python3
"""Wrapper body files (body-format-spec §2.4, issue 37) through every tool.

    wrapper_tools.py BIN_DIR SHARED_DIR EXAMPLES_DIR WORK_DIR

A one-line wrapper around the corpus URDF SR1.urdf (written at test time in WORK_DIR, naming
the URDF by a relative path) must be the model urdf2body makes of SR1.urdf but for what
Choreonoid's URDF loader reads differently (IMPORT.md, "Two readings"; in SR1.urdf only the
visuals naming a material that a later link defines, which the wrapper colours): the same
bodyinfo values (--format yaml), the same body2urdf and body2mjcf outputs (materials aside, which
are counted), no difference in bodydiff, and every other tool reads it. Its links must be those
of Choreonoid's reference of SR1.body, from which SR1.urdf was made (tree, joints, mass data,
frames). bodycheck on a wrapper around a URDF with a planted defect locates the finding at the
URDF's line and column. A wrapper around a .body is that model, with its linkInfo checked.
"""
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import yaml

BIN, SHARED, EXAMPLES, WORK = sys.argv[1:5]
failures = []


def run(tool, *args):
    result = subprocess.run([os.path.join(BIN, tool), *args], capture_output=True, timeout=300)
    return result.returncode, result.stdout.decode("utf-8", "replace"), result.stderr.decode("utf-8", "replace")


def expect(condition, message):
    if not condition:
        failures.append(message)
    return condition


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


# urdf2body's .body holds degrees and axis-angle rotations: read back, its numbers differ from the
# URDF's in the last bits (1.57 rad comes back as 1.5699999999999996). They are compared to this.
TOLERANCE = 1e-9
NUMBER = re.compile(r"-?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
worst = [0.0]


def close(a, b):
    if a == b:
        return True
    difference = abs(a - b) / max(1.0, abs(a), abs(b))
    worst[0] = max(worst[0], difference)
    return difference <= TOLERANCE


def same_values(a, b):
    """bodyinfo values equal, numbers to TOLERANCE."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same_values(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same_values(x, y) for x, y in zip(a, b))
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        return close(float(a), float(b))
    return a == b


def same_export(a, b):
    """Two exports with the same text around their numbers, and numbers equal to TOLERANCE."""
    if a is None or b is None:
        return a is b
    if NUMBER.sub("#", a) != NUMBER.sub("#", b):
        return False
    return all(close(float(x), float(y)) for x, y in zip(NUMBER.findall(a), NUMBER.findall(b)))


def zero_origin(match):
    """An <origin> of zeros to TOLERANCE is the default, which a writer leaves out when exact."""
    return "" if all(abs(float(x)) <= TOLERANCE for x in NUMBER.findall(match.group(0))) else match.group(0)


def identity_quat(match):
    """The same for an MJCF quat of (1, 0, 0, 0)."""
    q = [float(x) for x in NUMBER.findall(match.group(1))]
    return "" if len(q) == 4 and all(abs(a - b) <= TOLERANCE for a, b in zip(q, (1, 0, 0, 0))) else match.group(0)


def without_materials(text):
    """An export without its materials: definitions and references (URDF and MJCF)."""
    text = re.sub(r'\n *<material name="[^"]*">\s*<color rgba="[^"]*"/>\s*</material>', "", text)
    text = re.sub(r'\n *<material [^>]*/>', "", text)
    return re.sub(r' material="[^"]*"', "", text)


def coloured_visuals(urdf_path):
    """Visuals with a colour as Choreonoid's URDF loader reads them: an inline <color>, or a
    material name that the file defines anywhere (it collects every material first, IMPORT.md)."""
    robot = ET.parse(urdf_path).getroot()
    defined = {m.get("name") for m in robot.findall("material") if m.find("color") is not None}
    materials = [v.find("material") for v in robot.iter("visual")]
    defined |= {m.get("name") for m in materials if m is not None and m.find("color") is not None}
    return sum(1 for m in materials if m is not None and (m.find("color") is not None or m.get("name") in defined))


def export_text(path):
    """An export without its header comment (it names the file it came from) and without
    <origin> elements and quat attributes that are the default to rounding."""
    text = re.sub(r"<!--.*?-->", "", read(path), flags=re.S)
    text = re.sub(r' quat="([^"]*)"', identity_quat, text)
    return re.sub(r"\n *<origin [^>]*/>", zero_origin, text)


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)

# --- SR1: the wrapper against urdf2body's output -------------------------------------------
sr1 = os.path.join(SHARED, "corpus", "choreonoid", "SR1", "SR1.urdf")
wrapper = os.path.join(WORK, "sr1", "SR1.body")
write(wrapper, "model_file: " + os.path.relpath(sr1, os.path.dirname(wrapper)) + "\n")
imported = os.path.join(WORK, "imported", "SR1.body")
code, _, err = run("urdf2body", sr1, "-o", imported)
undefined_materials = err.count("[import-material]")  # urdf2body's order: defined later, so not found
expect(code in (0, 1) and os.path.exists(imported), f"urdf2body SR1.urdf: exit {code}\n{err[-2000:]}")

infos = []
for model in (wrapper, imported):
    code, out, err = run("bodyinfo", "--format", "yaml", model)
    if expect(code == 0, f"bodyinfo {model}: exit {code}\n{err[-2000:]}"):
        info = yaml.safe_load(out)
        info.pop("messages", None)  # the URDF's import warnings, which urdf2body printed instead
        infos.append(info)
if len(infos) == 2:
    a, b = infos
    expect(same_values(a, b), "bodyinfo of the wrapper differs from bodyinfo of urdf2body's SR1.body:\n"
           + "\n".join(f"  {k}: {a.get(k)!r:.300} != {b.get(k)!r:.300}" for k in sorted(set(a) | set(b))
                       if not same_values(a.get(k), b.get(k))))
    print(f"bodyinfo: {a.get('num_links')} links, {a.get('num_joints')} joints, total mass {a.get('total_mass')} kg: "
          f"every value equal, the largest relative difference {worst[0]:.1e}")

# Against Choreonoid: the reference of SR1.body (Choreonoid's BodyLoader), of which SR1.urdf is a
# translation. Its links' tree, joints, mass data and frames must be the wrapper's (SR1.urdf gives
# every link an <inertial>, so Choreonoid's URDF loader and urdfdom read it alike); the URDF's
# ranges (1.57 for pi/2), velocity limits, CHEST shapes, root pose and sensors are its own.
reference = yaml.safe_load(read(os.path.join(SHARED, "corpus", "reference", "SR1", "SR1.ref.yaml")))
if infos:
    mine = {link["name"]: link for link in infos[0]["links"]}
    compared = 0
    for field in ("total_mass", "num_links", "num_joints"):
        expect(same_values(infos[0][field], reference[field]), f"SR1 wrapper: {field} {infos[0][field]} != "
               f"Choreonoid's {reference[field]}")
    for link in reference["links"]:
        for field in ("parent", "joint_type", "joint_id", "joint_axis", "mass", "center_of_mass", "inertia",
                      "translation", "rotation", "world_translation_at_zero"):
            if field in link:
                compared += 1
                got = mine.get(link["name"], {}).get(field, "missing")
                expect(same_values(got, link[field]),
                       f"SR1 wrapper: {link['name']}.{field} {got} != Choreonoid's {link[field]}")
    print(f"SR1 wrapper against Choreonoid's reference of SR1.body: {compared} link values compared")

for tool, ext in (("body2urdf", "urdf"), ("body2mjcf", "xml")):
    outputs = []
    for name, model in (("wrapper", wrapper), ("imported", imported)):
        out = os.path.join(WORK, "exports", name, f"SR1.{ext}")  # the same stem: body2mjcf's meshdir
        os.makedirs(os.path.dirname(out), exist_ok=True)
        code, _, err = run(tool, model, "-o", out, "--allow-loss", "geometry,dynamics,joints,devices")
        expect(code in (0, 1), f"{tool} {name}: exit {code}\n{err[-2000:]}")
        outputs.append((code, export_text(out) if os.path.exists(out) else None))
    # The wrapper colours every visual whose material the file defines (Choreonoid's URDF loader
    # collects them all first); urdf2body leaves out those it reported undefined. Nothing else differs.
    coloured = coloured_visuals(sr1)
    uses = [len(re.findall(r'<material name="[^"]*"/>|material="', text or "")) for _, text in outputs]
    expect(uses == [coloured, coloured - undefined_materials] and undefined_materials > 0,
           f"{tool}: the wrapper's export has {uses[0]} material references, urdf2body's {uses[1]}; expected "
           f"{coloured} (Choreonoid's coloured visuals) and {coloured - undefined_materials}")
    expect(outputs[0][0] == outputs[1][0] and
           same_export(*(without_materials(text) if text else text for _, text in outputs)),
           f"{tool}: the wrapper's export differs from urdf2body's SR1.body's (materials aside)")
    print(f"{tool}: {uses[0]} material references in the wrapper's export, {uses[1]} in urdf2body's")
    print(f"{tool}: exit {outputs[0][0]} both, {len(NUMBER.findall(outputs[0][1] or ''))} numbers equal, "
          f"the largest relative difference so far {worst[0]:.1e}")

# bodydiff sees the same difference and only it: a material added to each visual that names a
# material a later link defines (urdf2body reported each of those undefined), nothing else.
code, out, err = run("bodydiff", imported, wrapper)
added = re.compile(r"^\S+:\d+:\d+: added: link '([^']*)': shape (\d+) material \w+: ")
coloured_by_wrapper = {m.groups() for line in out.splitlines() if (m := added.match(line))}
other = [line for line in out.splitlines()
         if line.strip() and not added.match(line) and not re.match(r"^\S+: In link '[^']*':$", line)]
expect(code == (1 if undefined_materials else 0) and not other and len(coloured_by_wrapper) == undefined_materials,
       f"bodydiff urdf2body's SR1.body and the wrapper: exit {code}, {len(coloured_by_wrapper)} visuals gain a "
       f"material (expected {undefined_materials}), other lines:\n" + "\n".join(other[:40]) + err[-2000:])
print(f"bodydiff: the wrapper colours {len(coloured_by_wrapper)} visuals more than urdf2body's SR1.body, "
      "nothing else differs")
for args in (["body2gltf", wrapper, "-o", os.path.join(WORK, "exports", "wrapper", "SR1.glb")],
             ["bodysim", "check", wrapper], ["bodycheck", wrapper],
             ["bodyview", wrapper, "-q", "--verbose", "-o", os.path.join(WORK, "exports", "wrapper", "SR1.html")]):
    if not os.path.exists(os.path.join(BIN, args[0])):
        continue  # bodysim and bodyview are optional
    code, out, err = run(*args)
    expect(code in (0, 1) and "load-wrapper" not in err,
           f"{args[0]} on the wrapper: exit {code}\n{err[-2000:]}")

# --- A finding inside the wrapped URDF is located there ------------------------------------
urdf = os.path.join(WORK, "defect", "arm.urdf")
write(urdf, """<?xml version="1.0"?>
<robot name="arm">
  <link name="base">
    <inertial>
      <mass value="1"/>
      <inertia ixx="1" iyy="1" izz="3" ixy="0" ixz="0" iyz="0"/>
    </inertial>
  </link>
</robot>
""")
defect_wrapper = os.path.join(WORK, "defect", "arm.body")
write(defect_wrapper, "model_file: arm.urdf\n")
code, out, err = run("bodycheck", "--color", "never", defect_wrapper)
err = out + err
expect(code == 1 and re.search(r"^\S*defect/arm\.urdf:6:7: error: .*\[inertia-triangle\]$", err, re.M),
       f"bodycheck on a wrapper around a URDF with A + B < C: exit {code}, expected 1 and the finding at "
       f"arm.urdf:6:7\n{err[-2000:]}")

# --- A wrapper around a .body, with linkInfo ------------------------------------------------
arm = os.path.join(EXAMPLES, "arm.body")
body_wrapper = os.path.join(WORK, "body", "arm.body")
write(body_wrapper, f"""model_file: {os.path.relpath(arm, os.path.dirname(body_wrapper))}
linkInfo:
  BASE: {{drive_stiffness: 100}}
  BASSE: {{drive_damping: 1}}
""")
code, out, err = run("bodycheck", "--color", "never", body_wrapper)
err = out + err
expect(code == 0 and re.search(r"^\S*body/arm\.body:4:3: warning: .*\"BASSE\".*\[wrapper-link-info\]$", err, re.M)
       and re.search(r"^\S*body/arm\.body:4:3: note: did you mean \"BASE\"\?$", err, re.M),
       f"bodycheck on a wrapper around arm.body with linkInfo for a missing link: exit {code}\n{err[-2000:]}")
code, out, err = run("bodydiff", arm, body_wrapper)
expect(code == 0 and not out, f"bodydiff arm.body and its wrapper: exit {code}\n{out[-2000:]}{err[-2000:]}")

for f in failures:
    print("FAIL:", f)
print(f"wrapper tools: {len(failures)} failures")
sys.exit(1 if failures else 0)
