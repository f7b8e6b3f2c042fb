#!/usr/bin/env python3
"""bench/bodyview_10k.py: a 10,000-link model in bodyview's page, in headless Chromium.

    bench/bodyview_10k.py [--build DIR] [--runs N] [--links N]

Writes a tree of N links (default 10,000: 100 chains of 100 revolute links, a box each) and
times, in one browser, N runs of (a) bodyview's page and (b) the peer: a page holding the same
three.js modules and body2gltf's GLB of the same model (visual only) that only parses the GLB
and draws one frame, the least any single-file three.js viewer of it does. Both are opened from file://;
the time is from the navigation's start to the first frame drawn (performance.now()).
Prints the medians, the ratio and whether bodyview's median first frame is within 5 s. Also prints
the time bodyview (the tool) takes to write the page. bench/README.md keeps the latest numbers.
"""
import argparse, base64, os, pathlib, statistics, subprocess, sys, tempfile, time

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests" / "bodyview"))
import cdp  # noqa: E402

PEER = """<!doctype html><html><head><meta charset="utf-8"><link rel="icon" href="data:,"></head>
<body style="margin:0"><canvas id="c" style="width:100%;height:100%;display:block"></canvas>
<script type="text/plain" id="glb">{glb}</script>{modules}
<script>
(async () => {{
  const bytes = (s) => {{ const t = atob(s.replace(/\\s+/g, '')); const a = new Uint8Array(t.length); for (let i = 0; i < t.length; ++i) a[i] = t.charCodeAt(i); return a; }};
  const names = {{ 'three': 'three.module.js', './three.core.js': 'three.core.js', '../utils/BufferGeometryUtils.js': 'BufferGeometryUtils.js', '../utils/SkeletonUtils.js': 'SkeletonUtils.js' }};
  const urls = {{}};
  for (const e of document.querySelectorAll('script.m')) {{
    const src = new TextDecoder().decode(bytes(e.textContent)).replace(/(\\bfrom\\s*)(['"])([^'"\\n]+)\\2/g, (m, f, q, n) => urls[names[n]] ? f + q + urls[names[n]] + q : m);
    urls[e.dataset.name] = URL.createObjectURL(new Blob([src], {{ type: 'text/javascript' }}));
  }}
  const THREE = await import(urls['three.module.js']);
  const {{ GLTFLoader }} = await import(urls['GLTFLoader.js']);
  const glb = bytes(document.getElementById('glb').textContent);
  const gltf = await new Promise((res, rej) => new GLTFLoader().parse(glb.buffer, '', res, rej));
  const scene = new THREE.Scene(); scene.add(gltf.scene); scene.add(new THREE.HemisphereLight(0xffffff, 0x404040, 2));
  const box = new THREE.Box3().setFromObject(gltf.scene), c = box.getCenter(new THREE.Vector3()), s = box.getSize(new THREE.Vector3()).length();
  const cam = new THREE.PerspectiveCamera(40, innerWidth / innerHeight, s / 1000, s * 50);
  cam.position.copy(c).add(new THREE.Vector3(s, s, s)); cam.lookAt(c);
  const r = new THREE.WebGLRenderer({{ canvas: document.getElementById('c'), antialias: true }});
  r.setSize(innerWidth, innerHeight, false); r.render(scene, cam);
  window.peerFirstFrameMs = performance.now();
}})();
</script></body></html>"""


def tree_model(links, per_chain=100):
    out = ["format: ChoreonoidBody", "format_version: 2.0", "name: Tree", "links:",
           "  - name: ROOT", "    joint_type: free", "    mass: 1",
           "    elements: [ { type: Shape, geometry: { type: Box, size: [0.1, 0.1, 0.1] } } ]"]
    for k in range(links - 1):
        chain, j = divmod(k, per_chain)
        parent = "ROOT" if j == 0 else f"L{chain}_{j - 1}"
        offset = f"[{0.2 * (chain % 10) - 0.9:.1f}, {0.2 * (chain // 10) - 0.9:.1f}, 0.1]" if j == 0 else "[0, 0, 0.05]"
        out += [f"  - name: L{chain}_{j}", f"    parent: {parent}", f"    translation: {offset}",
                "    joint_type: revolute", "    joint_axis: X", "    joint_range: [-90, 90]", "    mass: 0.1",
                "    inertia: [1e-4, 0, 0, 0, 1e-4, 0, 0, 0, 1e-4]",
                "    elements: [ { type: Shape, geometry: { type: Box, size: [0.02, 0.02, 0.04] } } ]"]
    return "\n".join(out) + "\n"


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--build", default=str(ROOT / "build"))
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--links", type=int, default=10000)
    a = p.parse_args()
    build = pathlib.Path(a.build)
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        model = tmp / "tree.body"
        model.write_text(tree_model(a.links))
        t0 = time.monotonic()
        r = subprocess.run([build / "bodyview", model, "-q", "-o", tmp / "tree.html"], capture_output=True, text=True)
        tool_s = time.monotonic() - t0
        if r.returncode not in (0, 1):
            sys.exit(f"bodyview failed: {r.stderr[-800:]}")
        subprocess.run([build / "body2gltf", model, "-q", "-o", tmp / "tree.glb"], check=False, capture_output=True)
        three = build / "bodyview_assets" / "three"
        modules = "".join(f'<script type="text/plain" class="m" data-name="{n}">'
                          f'{base64.b64encode((three / n).read_bytes()).decode()}</script>'
                          for n in ("three.core.js", "three.module.js", "BufferGeometryUtils.js", "SkeletonUtils.js",
                                    "GLTFLoader.js"))
        (tmp / "peer.html").write_text(PEER.format(glb=base64.b64encode((tmp / "tree.glb").read_bytes()).decode(),
                                                   modules=modules))
        browser = cdp.Browser(1000, 700)
        ours, peer = [], []
        try:
            for _ in range(a.runs):
                browser.open((tmp / "tree.html").as_uri(), timeout=300)
                ready = browser.evaluate("window.bodyview.ready", timeout=300)
                ours.append(ready["firstFrameMs"])
                if browser.console_errors():
                    sys.exit(f"console errors: {browser.console_errors()[:3]}")
                browser.open((tmp / "peer.html").as_uri(), timeout=300)
                peer.append(browser.evaluate(
                    "new Promise((ok) => { const t = () => window.peerFirstFrameMs ? ok(window.peerFirstFrameMs) : setTimeout(t, 20); t(); })",
                    timeout=300))
        finally:
            browser.close()
        size = (tmp / "tree.html").stat().st_size
    m, n = statistics.median(ours), statistics.median(peer)
    print(f"| bodyview page, {a.links} links ({size / 1e6:.1f} MB), navigation to first frame | {m:.0f} ms "
          f"({min(ours):.0f}-{max(ours):.0f}) | peer: three.js GLTFLoader + one frame of the same GLB | {n:.0f} ms "
          f"({min(peer):.0f}-{max(peer):.0f}) | {m / n:.2f} |")
    print(f"bodyview (the tool) wrote the page in {tool_s:.2f} s; median first frame within 5 s: "
          f"{'yes' if m < 5000 else 'NO'}")
    return 0 if m < 5000 else 1


if __name__ == "__main__":
    sys.exit(main())
