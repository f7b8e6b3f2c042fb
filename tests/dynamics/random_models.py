#!/usr/bin/env python3
"""Seeded random valid .body models for bodysim's population test, free-root (or, on request,
the same model with its root fixed to the world where the free one was released): trees of boxes,
cylinders, spheres and capsules whose mass data are exact for their shapes (closed forms
written here, not the project's), no two shapes overlapping (bounding spheres apart), masses
from grams to tens of kilograms, aspects from flat plates to tall posts, released level or
tilted so that they land on a face, tip over an edge, roll or tumble.

generate(seed, fixed_root=False) -> (text, description); the same seed always gives the same
model, and with fixed_root the same model with a fixed root.
Usage: random_models.py [--fixed-root] SEED [OUT.body]   (prints the model when OUT is not given)"""
import math
import random
import sys

SHAPES = ("Box", "Cylinder", "Sphere", "Capsule")


def shape_properties(kind, dims, density):
    """(mass, principal moments about the centre in the shape's own axes, bounding radius).
    Choreonoid's Cylinder and Capsule lie along their local Y; a Capsule's height is the length
    of its cylinder, without the two hemispheres."""
    if kind == "Box":
        x, y, z = dims
        m = density * x * y * z
        return m, (m * (y * y + z * z) / 12, m * (x * x + z * z) / 12, m * (x * x + y * y) / 12), 0.5 * math.sqrt(
            x * x + y * y + z * z)
    if kind == "Sphere":
        (r,) = dims
        m = density * 4 / 3 * math.pi * r**3
        return m, (0.4 * m * r * r,) * 3, r
    if kind == "Cylinder":
        r, h = dims
        m = density * math.pi * r * r * h
        side = m * (3 * r * r + h * h) / 12
        return m, (side, 0.5 * m * r * r, side), math.hypot(r, h / 2)
    r, h = dims  # Capsule: a cylinder and two hemispheres (one sphere) at its ends
    mc = density * math.pi * r * r * h
    ms = density * 4 / 3 * math.pi * r**3
    axial = 0.5 * mc * r * r + 0.4 * ms * r * r
    # Each hemisphere's centre of mass is 3r/8 from its flat face, which is h/2 from the centre.
    side = mc * (3 * r * r + h * h) / 12 + ms * (0.4 * r * r + h * h / 4 + 3 * h * r / 8)
    return mc + ms, (side, axial, side), r + h / 2


def random_shape(rng, size, role):
    """A shape about `size` across. role: 'post' (tall), 'plate' (flat), 'roller' (round, lying)
    or 'any'."""
    aspect = 10 ** rng.uniform(-0.6, 0.6)
    if role == "post":
        kind = rng.choice(("Box", "Cylinder", "Capsule"))
        aspect = rng.uniform(2.5, 6)
    elif role == "plate":
        kind = "Box"
        aspect = rng.uniform(0.1, 0.35)
    elif role == "roller":
        kind = rng.choice(("Cylinder", "Sphere", "Capsule"))
    else:
        kind = rng.choice(SHAPES)
    if kind == "Box":
        return kind, (size * rng.uniform(0.6, 1.6), size * rng.uniform(0.6, 1.6), size * aspect)
    if kind == "Sphere":
        return kind, (size / 2,)
    if kind == "Cylinder":
        return kind, (size / 2, size * aspect)
    return kind, (size / 2, size * aspect)


def rotation_matrix(axis, angle):
    x, y, z = axis
    n = math.sqrt(x * x + y * y + z * z)
    x, y, z = x / n, y / n, z / n
    c, s, t = math.cos(angle), math.sin(angle), 1 - math.cos(angle)
    return [[t * x * x + c, t * x * y - s * z, t * x * z + s * y], [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c]]


def fmt(v):
    return f"{v:.9g}"


def vec(values):
    return "[" + ", ".join(fmt(v) for v in values) + "]"


def link_text(name, parent, joint, shape, place, shape_rotation):
    """One link: its joint, a RigidBody at the shape's centre (mass data in the shape's own axes,
    turned with it) and the Shape inside it."""
    kind, dims, density = shape
    mass, moments, _ = shape_properties(kind, dims, density)
    lines = [f"  - name: {name}"]
    if parent:
        lines.append(f"    parent: {parent}")
    lines += [f"    {k}: {v}" for k, v in joint]
    lines += [
        "    elements:",
        "      - type: RigidBody",
        f"        translation: {vec(place)}",
    ]
    if shape_rotation:
        lines.append(f"        rotation: {vec(shape_rotation)}")
    lines += [
        f"        mass: {fmt(mass)}",
        f"        inertia: [{fmt(moments[0])}, 0, 0,  0, {fmt(moments[1])}, 0,  0, 0, {fmt(moments[2])}]",
        "        elements:",
        "          - type: Shape",
    ]
    if kind == "Box":
        geometry = f"{{ type: Box, size: {vec(dims)} }}"
    elif kind == "Sphere":
        geometry = f"{{ type: Sphere, radius: {fmt(dims[0])} }}"
    else:
        geometry = f"{{ type: {kind}, radius: {fmt(dims[0])}, height: {fmt(dims[1])} }}"
    lines.append(f"            geometry: {geometry}")
    return lines


def generate(seed, fixed_root=False):
    rng = random.Random(seed)
    size = 10 ** rng.uniform(math.log10(0.012), math.log10(0.5))  # 1.2 cm to 0.5 m across
    density = 10 ** rng.uniform(math.log10(200), math.log10(8000))  # foam to steel
    role = rng.choice(("post", "plate", "roller", "any", "any"))
    kind, dims = random_shape(rng, size, role)
    # Posts stand up (a Cylinder's or Capsule's axis is its Y: turned onto Z); rollers lie.
    root_shape_rotation = [1, 0, 0, 90] if role == "post" and kind != "Box" else None
    # Released level, or tilted so that it lands on an edge or a corner and tips.
    tilt = 0.0 if rng.random() < 0.4 else rng.uniform(3, 40)
    tilt_axis = (rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-0.3, 0.3))
    if abs(tilt_axis[0]) + abs(tilt_axis[1]) < 1e-3:
        tilt_axis = (1, 0, 0)
    shapes = [(kind, dims, density)]
    centres = [(0.0, 0.0, 0.0)]  # shape centres in the root frame (every link frame is parallel)
    bounds = [shape_properties(kind, dims, density)[2]]
    links = [
        link_text("ROOT", None, [("joint_type", "fixed" if fixed_root else "free"), ("translation", vec((0, 0, 1.0)))] +
                  ([("rotation", vec(tilt_axis + (tilt,)))] if tilt else []), shapes[0], (0, 0, 0),
                  root_shape_rotation)
    ]
    children = rng.choice((0, 0, 1, 1, 2, 3, 4))
    names = ["ROOT"]
    link_origins = [(0.0, 0.0, 0.0)]
    joint_id = 0
    for c in range(children):
        for _attempt in range(50):
            parent = rng.randrange(len(names))
            child_size = size * 10 ** rng.uniform(-0.6, 0.1)
            ckind, cdims = random_shape(rng, child_size, "any")
            cdensity = density * 10 ** rng.uniform(-0.7, 0.7)
            cbound = shape_properties(ckind, cdims, cdensity)[2]
            d = [rng.gauss(0, 1) for _ in range(3)]
            n = math.sqrt(sum(v * v for v in d)) or 1
            d = [v / n for v in d]
            gap = 0.05 * size + 0.002
            pc = centres[parent]
            origin = [pc[k] + d[k] * (bounds[parent] + gap / 2) for k in range(3)]  # the joint
            centre = [pc[k] + d[k] * (bounds[parent] + gap + cbound) for k in range(3)]
            if all(math.dist(centre, centres[k]) > bounds[k] + cbound + 1e-9 for k in range(len(centres))):
                break
        else:
            continue
        po = link_origins[parent]
        translation = [origin[k] - po[k] for k in range(3)]
        place = [centre[k] - origin[k] for k in range(3)]
        joint_kind = rng.choice(("revolute", "revolute", "prismatic", "fixed"))
        joint = [("joint_type", joint_kind), ("translation", vec(translation))]
        if joint_kind != "fixed":
            axis = rng.choice(([1, 0, 0], [0, 1, 0], [0, 0, 1], d))
            joint += [("joint_axis", vec(axis)), ("joint_id", str(joint_id))]
            joint_id += 1
            if joint_kind == "revolute":
                limit = rng.uniform(20, 170)
                joint.append(("joint_range", vec((-limit, limit))))
            else:
                joint.append(("joint_range", vec((-gap / 4, gap / 4))))  # metres: the shapes stay apart
        name = f"LINK{c + 1}"
        shape = (ckind, cdims, cdensity)
        rot = [rng.choice((1, 0)), rng.choice((1, 0)), 1, rng.choice((0, 90, 45))]
        links.append(link_text(name, names[parent], joint, shape, place, rot if rot[3] else None))
        names.append(name)
        centres.append(tuple(centre))
        bounds.append(cbound)
        link_origins.append(tuple(origin))
        shapes.append(shape)
    total = sum(shape_properties(*s)[0] for s in shapes)
    description = (f"seed {seed}{' fixed root' if fixed_root else ''}: {role} {kind} "
                   f"{len(names)} link{'s' if len(names) > 1 else ''}, "
                   f"{size * 100:.3g} cm, {total:.3g} kg, tilted {tilt:.3g}°")
    header = [
        f"# Random valid model (tests/dynamics/random_models.py), {description}",
        "format: ChoreonoidBody",
        "format_version: 2.0",
        "angle_unit: degree",
        f"name: Random{seed}",
        "root_link: ROOT",
        "links:",
    ]
    return "\n".join(header + [l for link in links for l in link]) + "\n", description


def main():
    args = sys.argv[1:]
    fixed_root = args[:1] == ["--fixed-root"]
    args = args[1:] if fixed_root else args
    if len(args) not in (1, 2):
        print(__doc__, file=sys.stderr)
        return 2
    text, _ = generate(int(args[0]), fixed_root)
    if len(args) == 2:
        with open(args[1], "w", encoding="utf-8") as f:
            f.write(text)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
