#!/usr/bin/env python3
"""The corpus links whose written inertia differs from their shapes' by more than a factor (issue 39).

usage: inertia_factor_table.py BODYINFO CORPUS_DIR [FACTOR (default 10)]

For every .body file under CORPUS_DIR, `bodyinfo --mass-from-geometry --format json` gives each
link's written mass properties and its shapes' (collision shapes, else visual ones) at the
written mass. The factor of a link is the largest ratio, either way, between its written and
computed principal moments, each sorted ascending (I1 <= I2 <= I3), both about their own centre of
mass: max over k of max(W_k / C_k, C_k / W_k). A written moment <= 0 makes the factor infinite.
Links with no written mass or no solid shape are not compared. Prints a Markdown table of the
links above FACTOR, largest first (a link that several models carry with the same numbers, as
SR1's variants do, is one row naming them all), and a summary line.
"""
import json
import math
import pathlib
import subprocess
import sys


def factor(written, computed):
    worst = 1.0
    for w, c in zip(sorted(written), sorted(computed)):
        if w <= 0 or c <= 0:
            return math.inf
        worst = max(worst, w / c, c / w)
    return worst


def main():
    bodyinfo, corpus = sys.argv[1], pathlib.Path(sys.argv[2])
    limit = float(sys.argv[3]) if len(sys.argv) > 3 else 10.0
    rows, compared, models = [], 0, 0
    for path in sorted(corpus.rglob("*.body")):
        r = subprocess.run([bodyinfo, "--mass-from-geometry", "--format", "json", "--no-config", str(path)],
                           capture_output=True, text=True)
        if r.returncode == 2 or not r.stdout.strip():
            print(f"<!-- {path.relative_to(corpus)}: bodyinfo exit {r.returncode} -->")
            continue
        models += 1
        for link in json.loads(r.stdout)["links"]:
            written, computed = link.get("written"), link.get("computed_at_written_mass")
            if not written or not computed or not (written.get("mass") or 0) > 0:
                continue
            compared += 1
            f = factor(written["principal_moments"], computed["principal_moments"])
            if f > limit:
                rows.append((f, str(path.relative_to(corpus)), link["name"], written, computed, link["shapes"]))
    # One row for a link that several models carry alike (SR1's variants): same name and numbers.
    fmt = lambda v: ", ".join(f"{x:.3g}" for x in v)
    grouped = {}
    for f, model, name, w, c, shapes in rows:
        key = (name, f"{w['mass']:.4g}", fmt(w["principal_moments"]), fmt(c["principal_moments"]), shapes)
        grouped.setdefault(key, [f, []])[1].append(model)
    print("| link | models | mass kg | written I1, I2, I3 kg·m² | from the shapes | factor |")
    print("|---|---|---|---|---|---|")
    for (name, mass, written, computed, shapes), (f, where) in sorted(grouped.items(),
                                                                      key=lambda kv: (-kv[1][0], kv[1][1], kv[0])):
        shown = "∞" if math.isinf(f) else f"{f:.3g}"
        print(f"| {name} | {', '.join(where)} | {mass} | {written} | {computed} ({shapes}) | {shown} |")
    print(f"\n{len(rows)} of {compared} links compared in {models} models differ by more than a factor of {limit:g}"
          f" ({len(grouped)} rows: links alike in several models share one)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
