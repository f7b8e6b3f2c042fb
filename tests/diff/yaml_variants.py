"""Rewrites of a .body file's YAML that leave the model the same (bodydiff's no-change tests).

Read with PyYAML's BaseLoader (every scalar a string, aliases shared) and written back with plain
scalars wherever YAML allows, so that no value changes its type on the way.
"""
import json

import yaml

# Key spellings the loader reads both ways (body-format-spec §2): snake_case and the legacy
# camelCase. Only pairs whose legacy key means nothing else elsewhere.
SPELLINGS = {
    "actuation_mode": "actuationMode", "center_of_mass": "centerOfMass", "crease_angle": "creaseAngle",
    "cross_section": "crossSection", "division_number": "divisionNumber", "extra_joints": "extraJoints",
    "gear_ratio": "gearRatio", "joint_axis": "jointAxis", "joint_id": "jointId", "joint_range": "jointRange",
    "joint_type": "jointType", "joint_velocity_range": "jointVelocityRange",
    "max_joint_velocity": "maxJointVelocity", "root_link": "rootLink", "rotor_inertia": "rotorInertia",
    "x_dimension": "xDimension", "z_dimension": "zDimension", "joint_id_offset": "jointIdOffset",
}
RESPELL = dict(SPELLINGS)
RESPELL.update({camel: snake for snake, camel in SPELLINGS.items()})


class _Dumper(yaml.emitter.Emitter, yaml.serializer.Serializer, yaml.representer.SafeRepresenter,
              yaml.resolver.BaseResolver):
    """Plain scalars: with no implicit resolvers, no string needs quotes to stay a string."""

    def __init__(self, stream, **kw):
        sort_keys = kw.pop("sort_keys", False)
        yaml.emitter.Emitter.__init__(self, stream, width=kw.pop("width", 4096), indent=kw.pop("indent", 2),
                                      allow_unicode=True, line_break=None, canonical=None)
        yaml.serializer.Serializer.__init__(self)
        yaml.representer.SafeRepresenter.__init__(self, default_style=None, default_flow_style=kw.pop(
            "default_flow_style", False), sort_keys=sort_keys)
        yaml.resolver.BaseResolver.__init__(self)


def load(text):
    return yaml.load(text, Loader=yaml.BaseLoader)


def dump(tree, sort_keys=False, indent=2, flow=False):
    return yaml.dump(tree, Dumper=_Dumper, sort_keys=sort_keys, indent=indent, default_flow_style=flow)


def expanded(tree):
    """No two places share a node: every alias written out in full."""
    return json.loads(json.dumps(tree))


def respelled(tree, extra_joint=False):
    """Every key of SPELLINGS in the other spelling. In an extra joint the legacy `jointAxis` is
    `axis` (a `joint_axis` key there is unknown)."""
    if isinstance(tree, dict):
        out = {}
        for k, v in tree.items():
            key = ("axis" if k == "jointAxis" else "jointAxis" if k == "axis" else k) if extra_joint \
                else RESPELL.get(k, k)
            out[key] = respelled(v, k in ("extra_joints", "extraJoints"))
        return out
    if isinstance(tree, list):
        return [respelled(v, extra_joint) for v in tree]
    return tree


def with_anchors(tree):
    """Equal sequences and mappings shared, so that the dumper writes them once (&anchor) and
    aliases them (*anchor) everywhere else."""
    seen = {}

    def walk(node):
        if isinstance(node, dict):
            node = {k: walk(v) for k, v in node.items()}
        elif isinstance(node, list):
            node = [walk(v) for v in node]
        else:
            return node
        return seen.setdefault(json.dumps(node, sort_keys=False), node)

    return walk(expanded(tree))


def first_mass_doubled(tree):
    """A real change, to prove the rewrites reach the model: the first `mass` value doubled.
    Returns None when the file has no numeric mass."""
    done = []

    def walk(node):
        if isinstance(node, dict):
            out = {}
            for k, v in node.items():
                if k == "mass" and not done and isinstance(v, str):
                    try:
                        out[k] = repr(float(v) * 2 + 1)
                        done.append(True)
                        continue
                    except ValueError:
                        pass
                out[k] = walk(v)
            return out
        if isinstance(node, list):
            return [walk(v) for v in node]
        return node

    result = walk(expanded(tree))
    return result if done else None
