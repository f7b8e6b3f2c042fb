#!/usr/bin/env python3
"""Compares two trees of *.ref.yaml files field by field: every key of the schema, not only the
ones conformance.py checks (link order, joint and device counts, camera clip distances, spot
light exponents, extra joints, loader messages). Used to check choreonoid_dump against the
corpus references it must reproduce.

usage: compare_refs.py EXPECTED_ROOT ACTUAL_ROOT
Prints one line per differing file (all its differences, or the first 5), then
'compare_refs: N/M files equal'. Exit 0 when all are equal.

Tolerances are those of shared/corpus/README.md: 1e-9 relative plus 1e-12 absolute for
numbers, 1e-3 m or 1 % of the box size for bounding boxes; strings must be equal.
"""
import math
import pathlib
import re
import sys

import yaml


class _Loader(yaml.SafeLoader):
    """YAML 1.2 floats: PyYAML's 1.1 rules read '1e-05' (no dot) as a string."""


_Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"""^(?:[-+]?(?:[0-9][0-9_]*)(?:\.[0-9_]*)?(?:[eE][-+]?[0-9]+)?
    |[-+]?\.[0-9_]+(?:[eE][-+]?[0-9]+)?
    |[-+]?\.(?:inf|Inf|INF)
    |\.(?:nan|NaN|NAN))$""", re.X),
    list("-+0123456789."))


def close(a, b, rel, abs_):
    if isinstance(a, (list, tuple)) or isinstance(b, (list, tuple)):
        return (isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)) and len(a) == len(b)
                and all(close(x, y, rel, abs_) for x, y in zip(a, b)))
    if isinstance(a, bool) or isinstance(b, bool) or isinstance(a, str) or isinstance(b, str):
        return a == b
    if a is None or b is None:
        return a is b
    a, b = float(a), float(b)
    if math.isinf(a) or math.isinf(b) or math.isnan(a) or math.isnan(b):
        return a == b or (math.isnan(a) and math.isnan(b))
    return abs(a - b) <= abs_ + rel * max(abs(a), abs(b))


def same(key, a, b):
    if key.endswith("_bbox") and a is not None and b is not None:
        size = max(abs(x) for x in a) if a else 1.0
        return close(b, a, 0.0, max(1e-3, 0.01 * size))
    return close(a, b, 1e-9, 1e-12)


def diff_items(where, expected, actual, out):
    """Key by key over the union of keys of two mappings (a key present on one side only is a
    difference too)."""
    for key in list(expected) + [k for k in actual if k not in expected]:
        if key not in expected or key not in actual:
            out.append(f"{where}{key}: {'absent' if key not in actual else actual[key]!r} "
                       f"!= {'absent' if key not in expected else expected[key]!r}")
        elif not same(key, expected[key], actual[key]):
            out.append(f"{where}{key}: {actual[key]!r} != {expected[key]!r}")


def diff(expected, actual):
    out = []
    top = {k: v for k, v in expected.items() if k not in ("links", "devices")}
    diff_items("", top, {k: v for k, v in actual.items() if k not in ("links", "devices")}, out)
    for kind in ("links", "devices"):
        exp_list, act_list = expected.get(kind) or [], actual.get(kind) or []
        exp_names = [x.get("name") for x in exp_list]
        act_names = [x.get("name") for x in act_list]
        if exp_names == act_names:  # by position: devices may share a name, often ""
            pairs = list(zip(exp_list, act_list))
        else:
            out.append(f"{kind} order: {act_names} != {exp_names}")
            act_by_name = {x.get("name"): x for x in act_list}
            pairs = [(item, act_by_name.get(item.get("name"))) for item in exp_list]
        for item, other in pairs:
            if other is None:
                out.append(f"{kind} {item.get('name')} missing")
            else:
                diff_items(f"{kind[:-1]} {item.get('name')}.", item, other, out)
    return out


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    expected_root, actual_root = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    equal = total = 0
    for exp_file in sorted(expected_root.rglob("*.ref.yaml")):
        rel = exp_file.relative_to(expected_root)
        total += 1
        act_file = actual_root / rel
        if not act_file.exists():
            print(f"{rel}: no such file in {actual_root}")
            continue
        problems = diff(yaml.load(exp_file.read_text(), Loader=_Loader) or {},
                        yaml.load(act_file.read_text(), Loader=_Loader) or {})
        if problems:
            more = f" (+{len(problems) - 5} more)" if len(problems) > 5 else ""
            print(f"{rel}: {len(problems)} differences: " + "; ".join(problems[:5]) + more)
        else:
            equal += 1
    print(f"compare_refs: {equal}/{total} files equal")
    sys.exit(0 if equal == total and total else 1)


if __name__ == "__main__":
    main()
