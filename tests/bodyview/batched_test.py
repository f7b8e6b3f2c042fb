#!/usr/bin/env python3
"""bodyview draws a large model batched (one BatchedMesh per material), and the batch follows.

usage: batched_test.py BODYVIEW BODYINFO OUT_DIR

Writes a 61-link tower with 30 boxes per link (1,830 visual meshes, over the page's batching
threshold of 1,500) and opens its page in headless Chromium: every mesh is batched, no console
error, linkMatrix equals bodyinfo --pose at a random pose, turning the first joint by 90 degrees
changes the render and turning it back restores it, and a selected link glows blue (its own
meshes are drawn instead of their batched copies).
"""
import base64, json, pathlib, random, sys

sys.path.insert(0, str(pathlib.Path(__file__).parent))
import cdp
from viewer_test import frames

SHOT = """(async () => {
  const url = window.bodyview.render();
  const img = new Image(); img.src = url; await img.decode();
  const c = document.createElement('canvas'); c.width = img.width; c.height = img.height;
  const g = c.getContext('2d'); g.drawImage(img, 0, 0);
  const d = g.getImageData(0, 0, c.width, c.height).data;
  let t = '';
  for (let i = 0; i < d.length; i += 0x8000) t += String.fromCharCode.apply(null, d.subarray(i, i + 0x8000));
  return btoa(t);
})()"""


def model(links=60, boxes=30):
    # A tower of bars: each link 5 cm above its parent, a bar of 30 boxes along x, turning about Z.
    bar = [f"      - {{ type: Shape, translation: [{0.02 * k:.2f}, 0, 0], geometry: {{ type: Box, size: [0.018, 0.1, 0.04] }} }}"
           for k in range(boxes)]
    out = ["format: ChoreonoidBody", "format_version: 2.0", "name: Batched", "links:",
           "  - name: ROOT", "    joint_type: free", "    mass: 1", "    elements:"] + bar
    for i in range(links):
        out += [f"  - name: L{i}", f"    parent: {'ROOT' if i == 0 else f'L{i - 1}'}", "    translation: [0, 0, 0.05]",
                "    joint_type: revolute", "    joint_axis: Z", "    joint_range: [-90, 90]", "    mass: 0.1",
                "    inertia: [1e-4, 0, 0, 0, 1e-4, 0, 0, 0, 1e-4]", "    elements:"] + bar
    return "\n".join(out) + "\n"


def changed(a, b, keep=lambda r, g, bl: True):
    return sum(1 for i in range(0, len(a), 4)
               if abs(a[i] - b[i]) + abs(a[i + 1] - b[i + 1]) + abs(a[i + 2] - b[i + 2]) > 30 and keep(b[i], b[i + 1], b[i + 2]))


def main():
    import subprocess
    tool, bodyinfo, out = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
    out.mkdir(parents=True, exist_ok=True)
    body, page = out / "batched.body", out / "batched.html"
    body.write_text(model())
    p = subprocess.run([tool, str(body), "-q", "-o", str(page)], capture_output=True, text=True)
    if p.returncode not in (0, 1):
        print(f"FAIL: bodyview rc={p.returncode}: {p.stderr[-600:]}")
        return 1
    failures = []
    browser = cdp.Browser(800, 600)
    try:
        browser.open(page.as_uri())
        browser.evaluate("window.bodyview.ready")
        batched = browser.evaluate("window.bodyview.batched()")
        if batched != 1830:
            failures.append(f"{batched} of 1830 meshes batched")
        rng = random.Random(29)
        q = {j["link"]: rng.uniform(j["min"], j["max"]) for j in browser.evaluate("window.bodyview.joints()")}
        got = browser.evaluate("(() => { const bv = window.bodyview, q = %s; for (const [k, v] of Object.entries(q)) bv.setJoint(k, v);"
                               " return Object.fromEntries(bv.links().map((l) => [l, bv.linkMatrix(l)])); })()" % json.dumps(q))
        want = frames(bodyinfo, body, q)
        worst = max(max(abs(a - b) for a, b in zip(got[l], want[l])) for l in want)
        if worst > 1e-6:
            failures.append(f"linkMatrix off by {worst:.3g}")
        browser.evaluate("window.bodyview.reset(), 1")
        first = base64.b64decode(browser.evaluate(SHOT))
        browser.evaluate("window.bodyview.setJoint('L0', Math.PI / 2), 1")
        turned = base64.b64decode(browser.evaluate(SHOT))
        browser.evaluate("window.bodyview.setJoint('L0', 0), 1")
        back = base64.b64decode(browser.evaluate(SHOT))
        browser.evaluate("window.bodyview.select('L30'), 1")
        selected = base64.b64decode(browser.evaluate(SHOT))
        browser.screenshot(str(out / "batched_selected.png"))
        sizes = {len(first), len(turned), len(back), len(selected)}
        if len(sizes) != 1:
            raise cdp.ChromiumError(f"the renders differ in size: {sorted(sizes)} bytes")
        area = len(first) // 4
        stats = {"turned": changed(first, turned) / area, "back": changed(first, back) / area,
                 "selected_blue": changed(back, selected, lambda r, g, b: b > r + 20) / area}
        print("pixel statistics: " + json.dumps({k: round(v, 4) for k, v in stats.items()}))
        if stats["turned"] < 0.01:
            failures.append("turning L0 by 90 degrees changed less than 1 % of the render: the batch does not follow")
        if stats["back"] > 0.001:
            failures.append("turning L0 back did not restore the render")
        if stats["selected_blue"] < 0.0005:
            failures.append("selecting L30 made nothing blue")
        if browser.console_errors():
            failures.append(f"console errors: {browser.console_errors()[:3]}")
    except cdp.ChromiumError as e:
        failures.append(str(e))
    finally:
        browser.close()
    for f in failures:
        print("FAIL: " + f)
    print("batched: " + ("FAIL" if failures else "OK"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
