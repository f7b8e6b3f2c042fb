#!/usr/bin/env python3
"""bodyview's page in headless Chromium, opened from file:// for every corpus model.

usage: viewer_test.py BODYVIEW BODYINFO CORPUS SIMPLETANK.body OUT_DIR [GLOB]

For every .body file of CORPUS/choreonoid (one browser for all of them, driven over the
DevTools protocol, cdp.py):
  * bodyview writes the page (exit 0 or 1), which loads with no console error or exception and
    asks for nothing but file:, blob: and data: URLs (no network);
  * the page has one slider per revolute and prismatic joint, as bodyinfo --format yaml lists them;
  * at 5 random poses (seeded, within each joint's slider range), every link's
    window.bodyview.linkMatrix equals bodyinfo --pose (bodyfmt::forward_kinematics) within 1e-6.
SimpleTank (the project's example): screenshots with the visual model only, with collision
geometry, and with collision and inertia boxes, kept in OUT_DIR; pixel statistics of the page's
own render (what changed between two renders, and its colour) show the cyan collision shapes and
the orange inertia boxes. Picking its turret from the link tree puts its file:line in the panel;
clicking its finding selects the link the finding is about.
"""
import base64, json, math, pathlib, random, re, subprocess, sys, time
import yaml

sys.path.insert(0, str(pathlib.Path(__file__).parent))
import cdp

TOL = 1e-6
POSES = 5

PIXELS = """(async () => {
  const bv = window.bodyview, set = %s;
  for (const [k, v] of Object.entries(bv.toggles())) await bv.setToggle(k, k in set ? set[k] : (k === 'visual' || k === 'tracks'));
  const url = bv.render();
  const img = new Image(); img.src = url; await img.decode();
  const c = document.createElement('canvas'); c.width = img.width; c.height = img.height;
  const g = c.getContext('2d'); g.drawImage(img, 0, 0);
  const data = g.getImageData(0, 0, c.width, c.height).data;
  let text = '';
  for (let i = 0; i < data.length; i += 0x8000) text += String.fromCharCode.apply(null, data.subarray(i, i + 0x8000));
  return { url, width: c.width, height: c.height, rgba: btoa(text) };
})()"""


def frames(bodyinfo, model, q):
    spec = ",".join(f"{k}={v!r}" for k, v in q.items())
    p = subprocess.run([bodyinfo, str(model), "-q", "--pose", spec], capture_output=True, text=True)
    if p.returncode not in (0, 1):
        raise RuntimeError(f"bodyinfo --pose: {p.stderr[-600:]}")
    out = {}
    for l in yaml.safe_load(p.stdout)["link_frames"]:
        R, t = l["rotation"], l["translation"]
        # column-major 4x4, as linkMatrix gives it
        out[l["name"]] = [R[0], R[3], R[6], 0, R[1], R[4], R[7], 0, R[2], R[5], R[8], 0, t[0], t[1], t[2], 1]
    return out


def movable_links(bodyinfo, model):
    p = subprocess.run([bodyinfo, str(model), "-q", "--format", "yaml"], capture_output=True, text=True)
    doc = yaml.safe_load(p.stdout)
    return [l["name"] for l in doc["links"] if l["joint_type"] in ("revolute", "prismatic")]


def check_model(browser, tool, bodyinfo, model, page, rng, failures):
    name = model.name
    p = subprocess.run([tool, str(model), "-q", "-o", str(page)], capture_output=True, text=True)
    if p.returncode not in (0, 1) or not page.exists():
        failures.append(f"{name}: bodyview rc={p.returncode}: {p.stderr[-400:]}")
        return None
    browser.open(page.as_uri())
    ready = browser.evaluate("window.bodyview.ready")
    errors = browser.console_errors()
    if errors:
        failures.append(f"{name}: console errors: {errors[:3]}")
    outside = [u for u in browser.requests() if not u.startswith(("file:", "blob:", "data:"))]
    if outside:
        failures.append(f"{name}: the page asked for {outside[:3]}")
    sliders = browser.evaluate("document.querySelectorAll('#joints input[type=range]').length")
    expected = movable_links(bodyinfo, model)
    joints = browser.evaluate("window.bodyview.joints()")
    if sliders != len(expected) or sorted(j["link"] for j in joints) != sorted(expected):
        failures.append(f"{name}: {sliders} sliders, joints() {[j['link'] for j in joints]}, movable joints {expected}")
    links = browser.evaluate("window.bodyview.links()")
    worst = 0.0
    for _ in range(POSES):
        q = {j["link"]: rng.uniform(j["min"], j["max"]) for j in joints}
        got = browser.evaluate("(() => { const bv = window.bodyview, q = %s;"
                               " for (const [k, v] of Object.entries(q)) bv.setJoint(k, v);"
                               " return Object.fromEntries(bv.links().map((l) => [l, bv.linkMatrix(l)])); })()"
                               % json.dumps(q))
        want = frames(bodyinfo, model, q)
        for link in links:
            e = max(abs(a - b) for a, b in zip(got[link], want[link]))
            worst = max(worst, e)
            if e > TOL:
                failures.append(f"{name}: {link} off by {e:.3g} at {q}")
                break
    return {"model": name, "links": len(links), "joints": len(joints), "first_frame_ms": round(ready["firstFrameMs"]),
            "worst": worst}


def changed(a, b, keep):
    n = 0
    for i in range(0, len(a), 4):
        if (abs(a[i] - b[i]) + abs(a[i + 1] - b[i + 1]) + abs(a[i + 2] - b[i + 2])) > 30 and keep(b[i], b[i + 1], b[i + 2]):
            n += 1
    return n


def simpletank(browser, tool, model, out, failures):
    page = out / "simpletank.html"
    p = subprocess.run([tool, str(model), "-q", "-o", str(page)], capture_output=True, text=True)
    if not page.exists():
        failures.append(f"SimpleTank: bodyview rc={p.returncode}: {p.stderr}")
        return
    browser.open(page.as_uri())
    browser.evaluate("window.bodyview.ready")
    shots = {}
    for label, toggles in (("visual", {}), ("collision", {"collision": True}), ("inertia", {"inertia": True}),
                           ("collision_inertia", {"collision": True, "inertia": True})):
        shot = browser.evaluate(PIXELS % json.dumps(toggles))
        shots[label] = base64.b64decode(shot["rgba"])
        (out / f"simpletank_{label}_render.png").write_bytes(base64.b64decode(shot["url"].split(",", 1)[1]))
        browser.screenshot(str(out / f"simpletank_{label}.png"))
    area = shot["width"] * shot["height"]
    cyan = changed(shots["visual"], shots["collision"], lambda r, g, b: b > r + 40 and g > r)
    orange = changed(shots["visual"], shots["inertia"], lambda r, g, b: r > b + 60 and r >= g)
    both = changed(shots["visual"], shots["collision_inertia"], lambda r, g, b: True)
    stats = {"area": area, "collision_cyan": cyan / area, "inertia_orange": orange / area, "both_changed": both / area}
    print("SimpleTank pixel statistics: " + json.dumps({k: round(v, 4) for k, v in stats.items()}))
    if not 0.02 <= stats["collision_cyan"] <= 0.6:
        failures.append(f"SimpleTank: collision geometry turned {stats['collision_cyan']:.1%} of the render cyan")
    if not 0.05 <= stats["inertia_orange"] <= 0.95:
        failures.append(f"SimpleTank: inertia boxes turned {stats['inertia_orange']:.1%} of the render orange")
    if stats["both_changed"] < max(stats["collision_cyan"], stats["inertia_orange"]):
        failures.append("SimpleTank: collision and inertia together changed less than one of them")
    # The tree selects a link and the panel says where it is written (its line found here).
    text = model.read_text().splitlines()
    line = next(i + 1 for i, t in enumerate(text) if re.search(r"name:\s*TURRET_P\b", t))
    panel = browser.evaluate("window.bodyview.select('TURRET_P'), document.getElementById('panel').textContent")
    if f"{model.name}:{line}" not in panel:
        failures.append(f"SimpleTank: the panel of TURRET_P does not say {model.name}:{line}: {panel[:300]}")
    # A finding, clicked, selects its link.
    findings = browser.evaluate("window.bodyview.findings()")
    for k, f in enumerate(findings):
        if f["link"]:
            picked = browser.evaluate(f"document.querySelectorAll('#findings li')[{k}].click(),"
                                      " document.querySelector('#tree span.selected').firstChild.textContent.trim()")
            if picked != f["link"]:
                failures.append(f"SimpleTank: finding {f['rule']} selected {picked}, not {f['link']}")
            break
    else:
        failures.append(f"SimpleTank: no finding names a link: {findings}")
    # Each finding starts with its file's name and line:col, in the side bar's width whatever the
    # folders (issue 47: a long path pushed line:col out of sight); the full path is its tooltip.
    shown = browser.evaluate("""[...document.querySelectorAll('#findings li')].map((li) => {
        const at = li.firstElementChild, side = document.getElementById('side').getBoundingClientRect();
        return { text: li.textContent, title: at ? at.title : null,
                 inside: at ? at.getBoundingClientRect().right <= side.right : false }; })""")
    for f, li in zip(findings, shown):
        placed = re.match(r"^(.*):(\d+):(\d+)$", f["where"])
        name = pathlib.Path(placed.group(1) if placed else f["where"]).name
        start = (f"{name}:{placed.group(2)}:{placed.group(3)}" if placed else name) + f": {f['severity']}:"
        if not li["text"].startswith(start) or li["title"] != f["where"] or not li["inside"]:
            failures.append(f"SimpleTank: finding {f['rule']} shows {li['text'][:120]!r} (tooltip {li['title']!r}, "
                            f"in the side bar: {li['inside']}), not {start!r} first with the path as tooltip")
            break
    if len(shown) != len(findings):
        failures.append(f"SimpleTank: {len(shown)} findings listed, {len(findings)} on the page")
    bodycheck_rules = sorted(f["rule"] for f in findings)
    print(f"SimpleTank findings on the page: {bodycheck_rules}")


def main():
    tool, bodyinfo, corpus, tank, out = sys.argv[1:6]
    corpus, tank, out = pathlib.Path(corpus), pathlib.Path(tank), pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    models = sorted((corpus / "choreonoid").rglob(sys.argv[6] if len(sys.argv) > 6 else "*.body"))
    rng = random.Random(29)
    failures, rows = [], []
    try:
        browser = cdp.Browser()
    except cdp.ChromiumError as e:
        print(f"FAIL: {e}")
        return 1
    start = time.monotonic()
    try:
        for model in models:
            page = out / "pages" / model.relative_to(corpus / "choreonoid").with_suffix(".html")
            page.parent.mkdir(parents=True, exist_ok=True)
            try:
                row = check_model(browser, tool, bodyinfo, model, page, rng, failures)
            except (cdp.ChromiumError, RuntimeError) as e:
                failures.append(f"{model.name}: {e}")
                row = None
            if row:
                rows.append(row)
        simpletank(browser, tool, tank, out, failures)
    finally:
        browser.close()
    for r in rows:
        print(f"{r['model']:32} {r['links']:4} links {r['joints']:3} joints  first frame {r['first_frame_ms']:5} ms"
              f"  worst |linkMatrix - FK| {r['worst']:.2g}")
    for f in failures:
        print("FAIL: " + f)
    print(f"{len(rows)} of {len(models)} models checked at {POSES} poses in {time.monotonic() - start:.0f} s; "
          f"screenshots in {out}: {'FAIL' if failures else 'OK'}")
    return 1 if failures or len(rows) != len(models) or not models else 0


if __name__ == "__main__":
    sys.exit(main())
