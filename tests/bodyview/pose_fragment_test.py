#!/usr/bin/env python3
"""bodyview starts at the file's pose, Reset returns to it, and the URL fragment sets toggles and joints.

usage: pose_fragment_test.py BODYVIEW BODYINFO OUT_DIR

A two-joint model whose revolute joint starts at 180 degrees inside the range [50, 310] (as
JACO2's ARM) and whose slider starts at 40 mm: opened in headless Chromium, every link's
linkMatrix equals bodyinfo --pose at the file's pose, each slider's label shows that value, and
Reset brings a moved joint back to it. `#collision=1&q.ARM=90&q.SLIDE=-20` sets those; hostile
fragments (an unknown joint, a value that is no number, a value outside the range, text that is
not URI-encoded, an unknown toggle) each leave a console message and no error, and an
out-of-range value is clamped to the range. Without -o, bodyview writes MODEL.html in the current
folder, and refuses to write over the model itself.
"""
import json, math, pathlib, subprocess, sys

sys.path.insert(0, str(pathlib.Path(__file__).parent))
import cdp
from viewer_test import frames

MODEL = """format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
name: Posed
links:
  - name: BASE
    joint_type: fixed
    mass: 1
    inertia: [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01]
    elements: [{ type: Shape, geometry: { type: Box, size: [0.2, 0.2, 0.1] } }]
  - name: ARM
    parent: BASE
    translation: [0, 0, 0.1]
    joint_type: revolute
    joint_id: 0
    joint_axis: Z
    joint_range: [50, 310]
    joint_angle: 180
    mass: 1
    inertia: [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01]
    elements: [{ type: Shape, translation: [0.15, 0, 0], geometry: { type: Box, size: [0.3, 0.05, 0.05] } }]
  - name: SLIDE
    parent: ARM
    translation: [0.3, 0, 0]
    joint_type: prismatic
    joint_id: 1
    joint_axis: X
    joint_range: [-0.05, 0.05]
    joint_displacement: 0.04
    mass: 0.5
    inertia: [0.001, 0, 0, 0, 0.001, 0, 0, 0, 0.001]
    elements: [{ type: Shape, geometry: { type: Box, size: [0.05, 0.05, 0.05] } }]
"""

STATE = """(() => { const bv = window.bodyview;
  return { q: Object.fromEntries(bv.joints().map((j) => [j.link, j.value])), toggles: bv.toggles(),
           labels: Array.from(document.querySelectorAll('#joints output')).map((o) => o.textContent),
           messages: bv.fragmentMessages || [],
           frames: Object.fromEntries(bv.links().map((l) => [l, bv.linkMatrix(l)])) }; })()"""


def worst(got, want):
    return max(max(abs(a - b) for a, b in zip(got[l], want[l])) for l in want)


def main():
    tool, bodyinfo, out = str(pathlib.Path(sys.argv[1]).resolve()), sys.argv[2], pathlib.Path(sys.argv[3]).resolve()
    out.mkdir(parents=True, exist_ok=True)
    body = out / "posed.body"
    body.write_text(MODEL)
    failures = []
    page = out / "posed.html"
    page.unlink(missing_ok=True)
    # No -o: MODEL.html in the current folder.
    p = subprocess.run([tool, "posed.body", "-q"], cwd=out, capture_output=True, text=True)
    if p.returncode != 0 or not page.is_file():
        failures.append(f"bodyview posed.body (no -o): rc={p.returncode}, posed.html written: {page.is_file()}: {p.stderr[-400:]}")
    # A model named NAME.html: the default page would be the model itself.
    clash = out / "clash.html"
    clash.write_text(MODEL)
    p = subprocess.run([tool, "clash.html", "-q"], cwd=out, capture_output=True, text=True)
    if p.returncode != 2 or clash.read_text() != MODEL:
        failures.append(f"bodyview clash.html (no -o) wrote over the model: rc={p.returncode}: {p.stderr[-400:]}")

    start = {"ARM": math.radians(180), "SLIDE": 0.04}
    browser = cdp.Browser(800, 600)
    try:
        browser.open(page.as_uri())
        browser.evaluate("window.bodyview.ready")
        s = browser.evaluate(STATE)
        if any(abs(s["q"][k] - v) > 1e-12 for k, v in start.items()):
            failures.append(f"the page starts at {s['q']}, not the file's pose {start}")
        if worst(s["frames"], frames(bodyinfo, body, start)) > 1e-6:
            failures.append("linkMatrix at the start differs from bodyinfo --pose at the file's pose")
        if s["labels"] != ["180.0°", "40.0 mm"]:
            failures.append(f"the sliders are labelled {s['labels']}, not ['180.0°', '40.0 mm']")
        browser.evaluate("window.bodyview.setJoint('ARM', 1), window.bodyview.setJoint('SLIDE', 0), window.bodyview.reset(), 1")
        s = browser.evaluate(STATE)
        if any(abs(s["q"][k] - v) > 1e-12 for k, v in start.items()):
            failures.append(f"Reset went to {s['q']}, not the file's pose {start}")

        # A query makes each open a new document (a new fragment alone would not load one).
        browser.open(page.as_uri() + "?2#collision=1&q.ARM=90&q.SLIDE=-20")
        browser.evaluate("window.bodyview.ready")
        s = browser.evaluate(STATE)
        want = {"ARM": math.radians(90), "SLIDE": -0.02}
        if not s["toggles"]["collision"]:
            failures.append("#collision=1 left collision off")
        if any(abs(s["q"][k] - v) > 1e-9 for k, v in want.items()) or s["messages"]:
            failures.append(f"#collision=1&q.ARM=90&q.SLIDE=-20 gave {s['q']} ({s['messages']}), not {want}")
        if worst(s["frames"], frames(bodyinfo, body, want)) > 1e-6:
            failures.append("linkMatrix after the fragment differs from bodyinfo --pose")
        if s["labels"] != ["90.0°", "-20.0 mm"]:
            failures.append(f"after the fragment the sliders are labelled {s['labels']}")

        # 20 degrees is below the range [50, 310]: clamped to 50, and said.
        browser.open(page.as_uri() + "?3#q.ARM=20&q.SLIDE=15")
        browser.evaluate("window.bodyview.ready")
        s = browser.evaluate(STATE)
        want = {"ARM": math.radians(50), "SLIDE": 0.015}
        if any(abs(s["q"][k] - v) > 1e-9 for k, v in want.items()) or len(s["messages"]) != 1:
            failures.append(f"#q.ARM=20&q.SLIDE=15 gave {s['q']} ({s['messages']}), not {want} with one message")

        hostile = "#q.NOPE=1&q.ARM=abc&q.SLIDE=&%E0%A4%A&frobnicate=1&collision=maybe&q.ARM=1e999&q.SLIDE=400"
        browser.open(page.as_uri() + "?4" + hostile)
        browser.evaluate("window.bodyview.ready")
        s = browser.evaluate(STATE)
        # q.ARM=1e999 is infinite, not a number it can take: skipped; q.SLIDE=400 mm clamped to 50 mm.
        want = {"ARM": math.radians(180), "SLIDE": 0.05}
        if any(abs(s["q"][k] - v) > 1e-9 for k, v in want.items()):
            failures.append(f"{hostile} gave {s['q']}, not {want}")
        if len(s["messages"]) != 8 or s["toggles"]["collision"]:
            failures.append(f"{hostile}: {len(s['messages'])} messages (8 expected), collision "
                            f"{s['toggles']['collision']}: {json.dumps(s['messages'])}")
        if browser.console_errors():
            failures.append(f"console errors: {browser.console_errors()[:3]}")
    except cdp.ChromiumError as e:
        failures.append(str(e))
    finally:
        browser.close()
    for f in failures:
        print("FAIL: " + f)
    print("pose and fragment: " + ("FAIL" if failures else "OK"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
