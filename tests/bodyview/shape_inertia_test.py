#!/usr/bin/env python3
"""bodyview's inertia boxes from the shapes beside the written ones (issue 39), in headless Chromium.

usage: shape_inertia_test.py BODYVIEW MODEL.body OUT_DIR

MODEL is tests/data/mass/inertia_boxes.body, whose tensors are known by hand:
  * BASE, 6 kg: written diag(0.1, 0.1, 0.5); its shape a box 0.6 x 0.3 x 0.2 turned 90 degrees
    about Z (0.3 x 0.6 x 0.2 along the link's axes) centred at (0.1, 0, 0.05);
  * ARM, 2 kg: written diag(0.03, 0.03, 0.0025); its shape a cylinder r = 0.05, h = 0.4 along Z
    centred at (0, 0, 0.2);
  * TIP, 0.5 kg: only in a RigidBody element, written diag(1e-4, 1e-4, 1e-4); its shape a sphere
    r = 0.035 (2/5 m r²) centred at the link origin.
The page data (window.bodyview.link) must hold, for the written tensor and for the shapes' at the
written mass, the box of uniform density with the same mass and principal moments: sides
sqrt(6 (I2 + I3 - I1) / m) and its two rotations (0 where negative), centred at the centre of
mass. The shapes' tensor comes from the textbook formulas here (a box m (b² + c²) / 12, a
cylinder m r² / 2 and m (3 r² + h²) / 12, a sphere 2/5 m r²), not from bodyfmt. BASE, which
bodycheck flags, shows the fix-it's values in its panel; ARM (plausible) has the shapes' box but
no fix-it; TIP has the shapes' box and no fix-it values (no link-level keys to write them in).
The shapes' boxes are drawn (green pixels appear when their toggle is switched on).
"""
import base64, json, math, pathlib, subprocess, sys

sys.path.insert(0, str(pathlib.Path(__file__).parent))
import cdp

TOL = 1e-9


def box_tensor(m, a, b, c):
    return [m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12]


def cylinder_z_tensor(m, r, h):
    side = m * (3 * r * r + h * h) / 12
    return [side, side, m * r * r / 2]


def equivalent_box(m, moments):
    s = sum(moments)
    return sorted(math.sqrt(max(0.0, 6 * (s - 2 * i) / m)) for i in moments)


def diagonal(d):
    return [d[0], 0, 0, 0, d[1], 0, 0, 0, d[2]]


GREEN = """(async () => {
  const bv = window.bodyview;
  const pixels = async () => {
    const img = new Image(); img.src = bv.render(); await img.decode();
    const c = document.createElement('canvas'); c.width = img.width; c.height = img.height;
    const g = c.getContext('2d'); g.drawImage(img, 0, 0);
    return g.getImageData(0, 0, c.width, c.height).data;
  };
  await bv.setToggle('visual', false);
  await bv.setToggle('shape_inertia', false);
  const off = await pixels();
  await bv.setToggle('shape_inertia', true);
  const on = await pixels();
  let green = 0;
  for (let i = 0; i < on.length; i += 4) {
    const changed = Math.abs(on[i] - off[i]) + Math.abs(on[i + 1] - off[i + 1]) + Math.abs(on[i + 2] - off[i + 2]) > 30;
    if (changed && on[i + 1] > on[i] + 40 && on[i + 1] > on[i + 2] + 20) ++green;
  }
  return green / (on.length / 4);
})()"""


def main():
    tool, model, out = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    out.mkdir(parents=True, exist_ok=True)
    page = out / "inertia_boxes.html"
    p = subprocess.run([tool, str(model), "-q", "-o", str(page)], capture_output=True, text=True)
    if p.returncode != 1 or not page.exists():  # 1: BASE's inertia-triangle error
        print(f"FAIL: bodyview exit {p.returncode} (1 expected): {p.stderr[-600:]}")
        return 1

    expected = {
        "BASE": {"mass": 6.0, "written": [0.1, 0.1, 0.5], "written_com": [0, 0, 0],
                 "shapes": box_tensor(6.0, 0.3, 0.6, 0.2), "shapes_com": [0.1, 0, 0.05], "fix": True},
        "ARM": {"mass": 2.0, "written": [0.03, 0.03, 0.0025], "written_com": [0, 0, 0.2],
                "shapes": cylinder_z_tensor(2.0, 0.05, 0.4), "shapes_com": [0, 0, 0.2], "fix": False},
        "TIP": {"mass": 0.5, "written": [1e-4] * 3, "written_com": [0, 0, 0],
                "shapes": [0.4 * 0.5 * 0.035 ** 2] * 3, "shapes_com": [0, 0, 0], "fix": False, "no_keys": True},
    }
    failures = []
    browser = cdp.Browser()
    try:
        browser.open(page.as_uri())
        browser.evaluate("window.bodyview.ready")
        for name, e in expected.items():
            link = browser.evaluate(f"window.bodyview.link({json.dumps(name)})")
            m = e["mass"]
            g = link.get("geometry")
            if not g or not link.get("inertia_box") or not g.get("inertia_box"):
                failures.append(f"{name}: no inertia box from the shapes in the page data: {json.dumps(link)[:300]}")
                continue
            for label, box, moments, com in (("written", link["inertia_box"], e["written"], e["written_com"]),
                                             ("shapes", g["inertia_box"], e["shapes"], e["shapes_com"])):
                want = equivalent_box(m, moments)
                got = sorted(box["size"])
                if any(abs(a - b) > TOL for a, b in zip(got, want)):
                    failures.append(f"{name}: the {label} tensor's box is {got}, the closed form {want}")
                centre = box["X"][12:15]
                if any(abs(a - b) > TOL for a, b in zip(centre, com)):
                    failures.append(f"{name}: the {label} tensor's box is centred at {centre}, not {com}")
                print(f"{name:5} {label:8} box {' x '.join(f'{v:.6f}' for v in got)} m  (closed form "
                      f"{' x '.join(f'{v:.6f}' for v in want)})")
            if any(abs(a - b) > TOL for a, b in zip(g["inertia"], diagonal(e["shapes"]))) or abs(g["mass"] - m) > TOL:
                failures.append(f"{name}: the shapes' tensor {g['inertia']} (mass {g['mass']}), "
                                f"by hand {diagonal(e['shapes'])} ({m})")
            if g["fix"] != e["fix"]:
                failures.append(f"{name}: fix-it offered {g['fix']}, expected {e['fix']}")
            if e.get("no_keys"):
                if g["fix_inertia"] is not None:
                    failures.append(f"{name}: fix-it values for a link without link-level keys: {g['fix_inertia']}")
            elif any(abs(a - b) > 1e-8 * max(1e-3, abs(b)) for a, b in zip(g["fix_inertia"], diagonal(e["shapes"]))):
                failures.append(f"{name}: the fix-it writes {g['fix_inertia']}, by hand {diagonal(e['shapes'])}")
            panel = browser.evaluate(f"window.bodyview.select({json.dumps(name)}),"
                                     " document.getElementById('panel').textContent")
            shows_fix = "--fix=geometry writes" in panel
            if shows_fix != e["fix"]:
                failures.append(f"{name}: the panel {'shows' if shows_fix else 'does not show'} the fix-it: {panel[:400]}")
            if e["fix"] and not all(f"{v:.9g}" in panel for v in e["shapes"]):
                failures.append(f"{name}: the panel does not show the fix-it's {e['shapes']}: {panel[:600]}")
        if "shape_inertia" not in browser.evaluate("window.bodyview.toggles()"):
            failures.append("no shape_inertia toggle")
        else:
            green = browser.evaluate(GREEN)
            print(f"shape_inertia turned {green:.1%} of the render green")
            if not 0.005 <= green <= 0.9:
                failures.append(f"the shapes' inertia boxes turned {green:.1%} of the render green")
        (out / "inertia_boxes.png").write_bytes(base64.b64decode(
            browser.evaluate("window.bodyview.setToggle('inertia', true).then(() => window.bodyview.render())")
            .split(",", 1)[1]))
        if browser.console_errors():
            failures.append(f"console errors: {browser.console_errors()[:3]}")
    except cdp.ChromiumError as err:
        failures.append(str(err))
    finally:
        browser.close()
    for f in failures:
        print("FAIL: " + f)
    print("OK" if not failures else f"{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
