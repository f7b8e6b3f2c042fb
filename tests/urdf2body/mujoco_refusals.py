#!/usr/bin/env python3
"""Does bodycheck find, on urdf2body's import, every inertia MuJoCo refuses in a URDF collection?

For every URDF that check_urdf accepts, each moving link's <inertial> is compiled alone by MuJoCo
(a one-body MJCF with a free joint and the URDF's full tensor), so the verdict is MuJoCo's own and
not bodyfmt's. The URDF is then imported with urdf2body and checked with bodycheck; each refused
link must have an inertia error naming it. Run by hand on public collections (not part of the
project, so not a ctest):

  tests/urdf2body/mujoco_refusals.py BUILD_DIR MJCHECK COLLECTION_DIR...

MJCHECK is a binary built from ../shared/tools/mjcheck.c. Links welded to their parent are left
out: MuJoCo fuses them into the moving body, and bodycheck judges that body.
"""
import os, subprocess, sys, tempfile, json, glob
import xml.etree.ElementTree as ET
build, mjcheck, roots = sys.argv[1], sys.argv[2], sys.argv[3:]
INERTIA_RULES = {"inertia-triangle", "inertia-not-positive-definite", "inertia-nonpositive-mass", "inertia-asymmetric", "inertia-tiny"}
tot = dict(urdf=0, accepted=0, imported=0, refused=0, found=0, missed=0)
missed = []
for root in roots:
    for urdf in sorted(glob.glob(os.path.join(root, "**/*.urdf"), recursive=True)):
        tot["urdf"] += 1
        if subprocess.run(["check_urdf", urdf], capture_output=True).returncode != 0: continue
        tot["accepted"] += 1
        try: doc = ET.parse(urdf).getroot()
        except ET.ParseError: continue
        children = {j.find("child").get("link"): j.get("type") for j in doc.iter("joint") if j.find("child") is not None}
        refused = {}
        for link in doc.iter("link"):
            name = link.get("name"); jt = children.get(name, "floating")
            if jt == "fixed": continue  # welded: MuJoCo fuses it, bodyfmt judges the moving body
            inert = link.find("inertial")
            if inert is None: continue
            m = inert.find("mass"); i = inert.find("inertia")
            if m is None or i is None: continue
            a = {k: i.get(k, "0") for k in ("ixx","iyy","izz","ixy","ixz","iyz")}
            mj = (f'<mujoco><compiler balanceinertia="false"/><worldbody><body><freejoint/>'
                  f'<inertial pos="0 0 0" mass="{m.get("value")}" fullinertia="{a["ixx"]} {a["iyy"]} {a["izz"]} {a["ixy"]} {a["ixz"]} {a["iyz"]}"/>'
                  f'</body></worldbody></mujoco>')
            with tempfile.NamedTemporaryFile("w", suffix=".xml", delete=False) as f: f.write(mj)
            out = subprocess.run([mjcheck, f.name], capture_output=True, text=True).stdout
            os.unlink(f.name)
            if '"error"' in out: refused[name] = json.loads(out)["error"]
        with tempfile.TemporaryDirectory() as d:
            body = os.path.join(d, "m.body")
            r = subprocess.run([f"{build}/urdf2body", "--no-meshes", urdf, "-o", body], capture_output=True, text=True)
            if not os.path.exists(body):
                r = subprocess.run([f"{build}/urdf2body", "--best-effort", "--no-meshes", urdf, "-o", body], capture_output=True, text=True)
            if not os.path.exists(body): print("no import:", urdf, r.stderr.strip().splitlines()[-1:]); continue
            tot["imported"] += 1
            js = subprocess.run([f"{build}/bodycheck", "--format", "json", "--no-config", body], capture_output=True, text=True).stdout
        flagged = {}
        try:
            for fnd in json.loads(js)["diagnostics"]:
                if fnd.get("rule") in INERTIA_RULES and fnd.get("severity") == "error":
                    msg = fnd.get("message", "")
                    for n in refused: 
                        if f'"{n}"' in msg: flagged[n] = (fnd["rule"], fnd.get("line"))
        except Exception as e: print("bad json", urdf, e); continue
        for n, why in refused.items():
            tot["refused"] += 1
            if n in flagged: tot["found"] += 1
            else: tot["missed"] += 1; missed.append((urdf, n, why))
print(json.dumps(tot))
for m in missed: print("MISSED", *m)
