#!/usr/bin/env python3
"""bodyview --serve follows the model in headless Chromium.

usage: serve_test.py BODYVIEW WORK_DIR

Writes a model of its own into WORK_DIR (main.body with a box and an STL mesh on BASE, and a
SubBody arm.body), starts `bodyview --serve main.body`, opens the page, and checks that the
page reloads and shows each change: BASE's mass, BASE's box size (the drawn box of BASE grows),
ARM's mass in the SubBody file, and the mesh file scaled (the drawn box grows again). Then a
YAML syntax error (an unclosed list): the page shows the diagnostic (file:line:col, source line, caret) over the
last good model, whose values stay; fixing the file clears it. SIGTERM stops the server (exit 0).
"""
import os, pathlib, re, signal, subprocess, sys, time

sys.path.insert(0, str(pathlib.Path(__file__).parent))
import cdp

MAIN = """format: ChoreonoidBody
format_version: 2.0
name: ServeTest
links:
  - name: BASE
    joint_type: free
    mass: {mass}
    elements:
      - type: Shape
        geometry: {{ type: Box, size: [{length}, 0.3, 0.1] }}
      - type: Shape
        geometry: {{ type: Resource, uri: part.stl }}
  - type: SubBody
    uri: arm.body
    parent: BASE
    translation: [0, 0, 0.2]
"""
ARM = """format: ChoreonoidBody
format_version: 2.0
links:
  - name: ARM
    joint_type: revolute
    joint_axis: Z
    mass: {mass}
    elements:
      - type: Shape
        geometry: {{ type: Box, size: [0.1, 0.1, 0.3] }}
"""


def stl(scale):
    v = [(0, 0, 0), (scale, 0, 0), (0, scale, 0), (0, 0, scale)]
    out = ["solid part"]
    for a, b, c in ((0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)):
        out += ["facet normal 0 0 0", "outer loop"] + [f"vertex {v[k][0]} {v[k][1]} {v[k][2]}" for k in (a, b, c)]
        out += ["endloop", "endfacet"]
    return "\n".join(out + ["endsolid part"]) + "\n"


def write(path, text):
    # A new modification time even on a file system with coarse times.
    before = path.stat().st_mtime_ns if path.exists() else 0
    path.write_text(text)
    while path.stat().st_mtime_ns == before:
        time.sleep(0.02)
        path.write_text(text)


def wait_for(browser, expression, want, timeout=30):
    """Polls `expression` (after the page is ready; the page may be reloading) until want(value)."""
    deadline, value = time.monotonic() + timeout, None
    while time.monotonic() < deadline:
        try:
            value = browser.evaluate(f"window.bodyview ? window.bodyview.ready.then(() => {expression}) : null", timeout=20)
            if value is not None and want(value):
                return value
        except cdp.ChromiumError:
            pass  # the document changed under the evaluation
        time.sleep(0.2)
    raise AssertionError(f"{expression} never became what was expected; last {value!r}")


def main():
    tool, work = sys.argv[1], pathlib.Path(sys.argv[2])
    work.mkdir(parents=True, exist_ok=True)
    main_body, arm_body, part = work / "main.body", work / "arm.body", work / "part.stl"
    write(main_body, MAIN.format(mass=2.0, length=0.4))
    write(arm_body, ARM.format(mass=1.0))
    write(part, stl(0.1))
    server = subprocess.Popen([tool, "--serve", "-q", str(main_body)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              text=True)
    failures = []
    browser = None
    try:
        url = server.stdout.readline().strip()
        if not url.startswith("http://127.0.0.1:"):
            raise AssertionError(f"bodyview --serve printed {url!r}: {server.stderr.read()[-800:] if server.poll() is not None else ''}")
        browser = cdp.Browser()
        browser.open(url)
        steps = [
            ("the first load", None, "window.bodyview.link('BASE').mass", lambda v: v == 2.0),
            ("BASE's mass", lambda: write(main_body, MAIN.format(mass=3.5, length=0.4)),
             "window.bodyview.link('BASE').mass", lambda v: v == 3.5),
            ("BASE's box", lambda: write(main_body, MAIN.format(mass=3.5, length=0.8)),
             "window.bodyview.drawnBox('BASE')", lambda b: abs((b[3] - b[0]) - 0.8) < 1e-5),
            ("ARM's mass in the SubBody", lambda: write(arm_body, ARM.format(mass=1.5)),
             "window.bodyview.link('ARM').mass", lambda v: v == 1.5),
            ("the mesh", lambda: write(part, stl(1.0)),
             "window.bodyview.drawnBox('BASE')", lambda b: abs(b[5] - 1.0) < 1e-5),
        ]
        for label, edit, expression, want in steps:
            if edit:
                edit()
            try:
                print(f"{label}: {wait_for(browser, expression, want)}")
            except AssertionError as e:
                failures.append(f"{label}: {e}")
        generation = wait_for(browser, "window.bodyview.serveStatus", lambda s: True)["generation"]
        write(main_body, MAIN.format(mass="[3.5", length=0.8))
        try:
            shown = wait_for(browser, "document.getElementById('error').hidden ? '' : document.getElementById('error').textContent",
                             lambda t: "error" in t)
            print("the syntax error, as the page shows it:\n" + shown)
            if not (re.search(r"main\.body:\d+:\d+: fatal error: .*\[yaml-syntax\]\n.*\n *\^", shown)):
                failures.append(f"the diagnostic has no location, source line or caret: {shown!r}")
            kept = browser.evaluate("[window.bodyview.link('BASE').mass, window.bodyview.serveStatus.generation,"
                                    " window.bodyview.drawnBox('BASE')]")
            if kept[0] != 3.5 or kept[1] != generation or abs(kept[2][5] - 1.0) > 1e-5:
                failures.append(f"the last good model was not kept: {kept}, generation {generation}")
        except AssertionError as e:
            failures.append(f"the syntax error: {e}")
        write(main_body, MAIN.format(mass=4.0, length=0.8))
        try:
            wait_for(browser, "[window.bodyview.link('BASE').mass, document.getElementById('error').hidden]",
                     lambda v: v == [4.0, True])
        except AssertionError as e:
            failures.append(f"after the fix: {e}")
        if browser.console_errors():
            failures.append(f"console errors: {browser.console_errors()}")
    except (AssertionError, cdp.ChromiumError) as e:
        failures.append(str(e))
    finally:
        if browser:
            browser.close()
        server.send_signal(signal.SIGTERM)
        try:
            rc = server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            server.kill()
            rc = "hung"
        log = server.stderr.read()
    if rc != 0:
        failures.append(f"bodyview --serve exited {rc} on SIGTERM")
    print("server log:\n" + "\n".join(l for l in log.splitlines() if l.startswith("bodyview:")))
    for f in failures:
        print("FAIL: " + f)
    print("serve: " + ("FAIL" if failures else "OK"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
