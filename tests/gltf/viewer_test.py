#!/usr/bin/env python3
"""A real viewer: three.js's GLTFLoader in headless Chromium shows body2gltf's SimpleTank right.

usage: viewer_test.py BODY2GLTF MODEL.body NPM_PREFIX OUT_DIR

Exports the model to OUT_DIR/simpletank.glb, serves it, viewer.html and NPM_PREFIX/node_modules
(npm three) on a loopback port, and loads the page in headless Chromium (Debian `chromium`,
flags from ../shared/spec/toolchain.md). The page renders the model and posts the PNG and
per-link pixel statistics back. Asserts what a person would check:
  * the chassis covers a plausible part of the image (3 %-60 %) and shows its green;
  * the turret is above the chassis in the image (its top row and its centroid);
  * the Camera device is found by name in the loaded scene, as a camera.
Keeps OUT_DIR/simpletank_view.png (the render) and OUT_DIR/simpletank_screenshot.png.
"""
import base64, http.server, json, os, pathlib, shutil, subprocess, sys, tempfile, threading

def main():
    tool, model, npm, out = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3]), pathlib.Path(sys.argv[4])
    out.mkdir(parents=True, exist_ok=True)
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if not chromium:
        print("chromium is not installed (README command 2 installs Debian's chromium)")
        return 1
    modules = npm / "node_modules"
    if not (modules / "three" / "examples" / "jsm" / "loaders" / "GLTFLoader.js").exists():
        print(f"npm three is not installed in {npm} (README command 2 installs it)")
        return 1
    glb = out / "simpletank.glb"
    p = subprocess.run([tool, str(model), "-o", str(glb), "-q"], capture_output=True, text=True)
    if p.returncode not in (0, 1):
        print(f"body2gltf failed rc={p.returncode}: {p.stderr}")
        return 1
    page = pathlib.Path(__file__).with_name("viewer.html")
    posted = {}
    done = threading.Event()

    class Handler(http.server.BaseHTTPRequestHandler):
        def log_message(self, *args):
            pass

        def do_GET(self):
            path = self.path.split("?")[0]
            if path == "/":
                f = page
            elif path == "/model.glb":
                f = glb
            elif path.startswith("/node_modules/"):
                f = (modules / path[len("/node_modules/"):]).resolve()
                if modules.resolve() not in f.parents:
                    f = None
            else:
                f = None
            if f is None or not f.is_file():
                self.send_response(404)
                self.end_headers()
                return
            data = f.read_bytes()
            ctype = {".html": "text/html", ".js": "text/javascript", ".glb": "model/gltf-binary"}.get(f.suffix,
                                                                                                    "application/octet-stream")
            self.send_response(200)
            self.send_header("Content-Type", ctype)
            self.send_header("Content-Length", str(len(data)))
            self.end_headers()
            self.wfile.write(data)

        def do_POST(self):
            body = self.rfile.read(int(self.headers.get("Content-Length", 0)))
            posted[self.path] = body
            self.send_response(200)
            self.end_headers()
            if self.path == "/result":
                done.set()

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    url = f"http://127.0.0.1:{server.server_address[1]}/"
    with tempfile.TemporaryDirectory() as profile:
        cmd = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
               "--disable-component-update", "--disable-sync", "--no-first-run", "--enable-unsafe-swiftshader",
               f"--user-data-dir={profile}", "--window-size=640,480", "--virtual-time-budget=20000",
               f"--screenshot={out / 'simpletank_screenshot.png'}", url]
        try:
            proc = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
        except subprocess.TimeoutExpired:
            print("chromium timed out")
            return 1
        done.wait(10)
    server.shutdown()
    if "/result" not in posted:
        print(f"the page posted no result; chromium rc={proc.returncode}: {proc.stderr[-1500:]}")
        return 1
    result = json.loads(posted["/result"])
    if "error" in result:
        print("the page failed: " + result["error"])
        return 1
    if "/render.png" in posted:
        data = posted["/render.png"].decode()
        (out / "simpletank_view.png").write_bytes(base64.b64decode(data.split(",", 1)[1]))
    print(json.dumps(result, indent=1))
    failures = []
    area = result["width"] * result["height"]
    chassis = result["stats"].get("CHASSIS")
    turret = result["stats"].get("TURRET_Y")
    if not chassis or not turret:
        failures.append(f"links seen: {result['links']}")
    else:
        frac = chassis["pixels"] / area
        if not 0.03 <= frac <= 0.6:
            failures.append(f"the chassis covers {frac:.1%} of the image")
        green = chassis["green_dominant"] / max(1, chassis["pixels"])
        if green < 0.8:
            failures.append(f"only {green:.0%} of the chassis pixels show its green")
        if not turret["pixels"] or not (turret["top"] < chassis["top"] and turret["centroid_y"] < chassis["centroid_y"]):
            failures.append(f"the turret (top {turret['top']}, centroid {turret['centroid_y']}) is not above the "
                            f"chassis (top {chassis['top']}, centroid {chassis['centroid_y']})")
    if not result["camera_found"]:
        failures.append(f"no camera named 'Camera' in the scene (glTF cameras: {result['gltf_cameras']})")
    if result["turret_joint_type"] != "revolute":
        failures.append(f"TURRET_Y extras joint_type is {result['turret_joint_type']}")
    for f in failures:
        print("FAIL: " + f)
    print(f"viewer: {'FAIL' if failures else 'OK'}; render kept at {out / 'simpletank_view.png'}")
    return 1 if failures else 0

if __name__ == "__main__":
    sys.exit(main())
