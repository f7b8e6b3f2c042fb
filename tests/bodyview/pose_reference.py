#!/usr/bin/env python3
"""bodyinfo --pose (bodyfmt::forward_kinematics) against Choreonoid's loader values.

usage: pose_reference.py BODYINFO CORPUS

For every corpus model Choreonoid loaded (CORPUS/reference/*.ref.yaml, loaded: true):
  * at the zero pose, each link's origin relative to the root, in root axes, equals the
    reference's world_translation_at_zero, and the root frame equals root_translation/rotation;
  * at 3 random poses (seeded), every link frame equals forward kinematics computed here from
    the reference's own link offsets, joint types and axes (body-format-spec §6.1: the joint at
    the link origin, a revolute turning about its normalised axis, a prismatic sliding along
    the axis as loaded), within 1e-6;
  * a random pose moves some link of every model with a movable joint (the check can fail).
"""
import math, pathlib, random, subprocess, sys
import yaml

TOL = 1e-6


def mul(A, B):
    return [[sum(A[i][k] * B[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def frame(rot9, t):
    return [[rot9[0], rot9[1], rot9[2], t[0]], [rot9[3], rot9[4], rot9[5], t[1]], [rot9[6], rot9[7], rot9[8], t[2]],
            [0, 0, 0, 1]]


def motion(kind, axis, q):
    if kind == "revolute" and q:
        n = math.sqrt(sum(a * a for a in axis))
        x, y, z = (a / n for a in axis)
        c, s, C = math.cos(q), math.sin(q), 1 - math.cos(q)
        return frame([c + x * x * C, x * y * C - z * s, x * z * C + y * s,
                      y * x * C + z * s, c + y * y * C, y * z * C - x * s,
                      z * x * C - y * s, z * y * C + x * s, c + z * z * C], [0, 0, 0])
    if kind == "prismatic" and q:
        return frame([1, 0, 0, 0, 1, 0, 0, 0, 1], [a * q for a in axis])
    return frame([1, 0, 0, 0, 1, 0, 0, 0, 1], [0, 0, 0])


def reference_fk(ref, q):
    X = {}
    for l in ref["links"]:
        if l["parent"] is None:
            base = frame(ref["root_rotation"], ref["root_translation"])
        else:
            base = mul(X[l["parent"]], frame(l["rotation"], l["translation"]))
        X[l["name"]] = mul(base, motion(l["joint_type"], l.get("joint_axis", [0, 0, 1]), q.get(l["name"], 0.0)))
    return X


def bodyinfo_pose(tool, model, q):
    spec = ",".join(f"{k}={v!r}" for k, v in q.items())
    p = subprocess.run([tool, str(model), "-q", "--pose", spec], capture_output=True, text=True)
    if p.returncode not in (0, 1):
        raise RuntimeError(f"bodyinfo --pose rc={p.returncode}: {p.stderr[-800:]}")
    doc = yaml.safe_load(p.stdout)
    return {l["name"]: frame(l["rotation"], l["translation"]) for l in doc["link_frames"]}


def worst(A, B):
    return max(abs(A[i][j] - B[i][j]) for i in range(3) for j in range(4))


def joint_sample(rng, l):
    lo, hi = l["joint_range"]
    if l["joint_type"] == "revolute":
        lo, hi = max(lo, -math.pi), min(hi, math.pi)
    else:
        lo, hi = max(lo, -0.5), min(hi, 0.5)
    return rng.uniform(lo, hi) if hi > lo else lo


def main():
    tool, corpus = sys.argv[1], pathlib.Path(sys.argv[2])
    rng = random.Random(29)
    failures, checked, links_checked = [], 0, 0
    for ref_path in sorted((corpus / "reference").rglob("*.ref.yaml")):
        ref = yaml.safe_load(ref_path.read_text())
        if not ref.get("loaded"):
            continue
        rel = ref_path.relative_to(corpus / "reference")
        model = corpus / "choreonoid" / str(rel).replace(".ref.yaml", ".body")
        checked += 1
        got = bodyinfo_pose(tool, model, {})
        root = got[ref["links"][0]["name"]]
        if worst(root, frame(ref["root_rotation"], ref["root_translation"])) > TOL:
            failures.append(f"{rel}: root frame {root} differs from the reference")
        for l in ref["links"]:
            X = got.get(l["name"])
            if X is None:
                failures.append(f"{rel}: no frame for link {l['name']}")
                continue
            d = [X[i][3] - root[i][3] for i in range(3)]
            p = [sum(root[k][i] * d[k] for k in range(3)) for i in range(3)]
            if max(abs(a - b) for a, b in zip(p, l["world_translation_at_zero"])) > TOL:
                failures.append(f"{rel}: {l['name']} at {p}, reference {l['world_translation_at_zero']}")
            links_checked += 1
        movable = [l for l in ref["links"] if l["joint_type"] in ("revolute", "prismatic")]
        zero = reference_fk(ref, {})
        for _ in range(3):
            q = {l["name"]: joint_sample(rng, l) for l in movable}
            got = bodyinfo_pose(tool, model, q)
            want = reference_fk(ref, q)
            off = [(worst(got[name], W), name) for name, W in want.items()]
            if max(off)[0] > TOL:
                failures.append(f"{rel}: {max(off)[1]} off by {max(off)[0]:.3g} at {q}")
            moved = max(worst(W, zero[name]) for name, W in want.items())
            if movable and any(q.values()) and moved < 1e-9:
                failures.append(f"{rel}: a random pose moved no link")
    for f in failures[:40]:
        print("FAIL: " + f)
    print(f"{checked} models, {links_checked} links at the zero pose, 3 random poses each: "
          f"{'FAIL' if failures else 'OK'}")
    return 1 if failures or checked < 40 else 0


if __name__ == "__main__":
    sys.exit(main())
