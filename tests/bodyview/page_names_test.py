#!/usr/bin/env python3
"""Whatever text a model carries, bodyview's page keeps its data and loads (issue 34).

usage: page_names_test.py BODYVIEW WORK_DIR [MODELS]

A property test over random names through the real page writer: MODELS (default 60) models whose
model name, link names, joint names, file name and a comment on a line with a finding are drawn
from HTML-significant pieces (`<!--`, `<script>`, `</script`, `-->`, `&`, `<`, `>`, U+2028,
U+2029, quotes, backslashes, `/collision`, `/visual`) and other text. For each page: the data
<script> holds none of `<`, `>`, `&`, U+2028 or U+2029 (so the HTML tokenizer cannot end it
early or change its state, whatever the text), and its JSON gives back every name byte for
byte. Then headless Chromium loads the pages of the first few models and of one whose links are
named `X/collision`, `X/visual` with children (names are data: no suffix convention of the GLB's
node names may collide with them): every link is found, the collision geometry loads, no error.
"""
import json, pathlib, random, re, subprocess, sys

sys.path.insert(0, str(pathlib.Path(__file__).parent))
import cdp

PIECES = ["<!--", "<script>", "</script", "</SCRIPT >", "-->", "<!--<script>", "&", "&amp;", "<", ">", "\u2028",
          "\u2029", '"', "'", "\\", "/", "/collision", "/visual", "é", "漢", "😀", " ", "a", "B", "_", "0", "]]>",
          "<![CDATA[", "</style", "<\\/", "\\u003c"]
FORBIDDEN = ["<", ">", "&", "\u2028", "\u2029"]


def random_name(rng):
    return "".join(rng.choice(PIECES) for _ in range(rng.randint(1, 6))).strip() or "a"


def quoted(text):
    """A YAML double-quoted scalar: escapes for what libyaml would read as a line break."""
    out = text.replace("\\", "\\\\").replace('"', '\\"')
    return '"' + out.replace("\u2028", "\\L").replace("\u2029", "\\P") + '"'


def model_text(name, links, comment):
    lines = ["format: ChoreonoidBody", "format_version: 2.0", f"name: {quoted(name)}", "links:"]
    for i, (link, joint) in enumerate(links):
        lines += [f"  - name: {quoted(link)}"]
        if i == 0:
            lines += ["    joint_type: free"]
        else:
            lines += [f"    parent: {quoted(links[i - 1][0])}", "    joint_type: revolute", f"    joint_id: {i - 1}",
                      f"    joint_name: {quoted(joint)}", "    joint_axis: Z", "    translation: [0.3, 0, 0]"]
        lines += ["    mass: 1",
                  # 15 times a box's inertia: a warning on this line, whose text the page shows
                  f"    inertia: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1]  # {comment}",
                  "    elements:", "      - type: Shape", "        geometry: { type: Box, size: [0.2, 0.2, 0.2] }"]
    return "\n".join(lines) + "\n"


def data_script(html):
    start = html.index('<script type="application/json" id="bv-data">') + len('<script type="application/json" id="bv-data">')
    end = re.compile(r"</script", re.I).search(html, start).start()
    return html[start:end]


def file_safe(text):
    return re.sub(r"[/\x00]", "_", text)[:60]


def main():
    tool, work = sys.argv[1], pathlib.Path(sys.argv[2])
    count = int(sys.argv[3]) if len(sys.argv) > 3 else 60
    work.mkdir(parents=True, exist_ok=True)
    rng = random.Random(34)
    failures, pages = [], []
    cases = [("X/collision", [("X/collision", ""), ("X/visual", "X/collision"), ("Y/collision/collision", "j/visual"),
                             ("Y", "Y/collision")], "X/collision")]
    for _ in range(count):
        links = [(random_name(rng), random_name(rng)) for _ in range(rng.randint(1, 4))]
        if len({l for l, _ in links}) < len(links) or len({j for _, j in links[1:]}) < len(links) - 1:
            continue  # a duplicate name is a bodycheck error, not this test's subject
        # U+2028 and U+2029 end a comment in YAML 1.1 (libyaml): the comment goes without them.
        comment = re.sub("[\u2028\u2029]", "", random_name(rng)) or "<!--<script>"
        cases.append((random_name(rng), links, comment))
    for k, (name, links, comment) in enumerate(cases):
        folder = work / f"case{k}"
        folder.mkdir(exist_ok=True)
        model = folder / (file_safe(name) + ".body")
        model.write_text(model_text(name, links, comment), encoding="utf-8")
        page = folder / "page.html"
        page.unlink(missing_ok=True)
        run = subprocess.run([tool, str(model), "-q", "-o", str(page)], capture_output=True, text=True)
        if run.returncode not in (0, 1) or not page.exists():
            failures.append(f"case {k} {name!r}: bodyview exit {run.returncode}: {run.stderr[-400:]}")
            continue
        html = page.read_text(encoding="utf-8")
        script = data_script(html)
        found = [c for c in FORBIDDEN if c in script]
        if found:
            failures.append(f"case {k} {name!r}: the data <script> holds {found}")
        try:
            data = json.loads(script)
        except json.JSONDecodeError as e:
            failures.append(f"case {k} {name!r}: the data <script> is not its JSON ({e}): ...{script[-200:]!r}")
            continue
        got = (data["model"], [l["name"] for l in data["links"]], [l["joint"] for l in data["links"][1:]])
        want = (name, [l for l, _ in links], [j for _, j in links[1:]])
        if got != want:
            failures.append(f"case {k}: names came back as {got!r}, not {want!r}")
        if not data["file"].endswith(model.name):
            failures.append(f"case {k}: the file came back as {data['file']!r}")
        if not any(comment in f["text"] for f in data["findings"]):
            failures.append(f"case {k}: no finding shows the line with the comment {comment!r}")
        pages.append((k, page, want[1]))
    browser = None
    try:
        browser = cdp.Browser()
        for k, page, names in pages[:6]:
            browser.open(page.as_uri())
            try:
                got = browser.evaluate("window.bodyview.ready.then(() => window.bodyview.links())")
                browser.evaluate("window.bodyview.setToggle('collision', true).then(() => 1)")
                drawn = [browser.evaluate(f"window.bodyview.drawnBox({json.dumps(n)})") for n in names]
            except cdp.ChromiumError as e:
                failures.append(f"case {k}: the page does not load: {e}")
                continue
            if got != names:
                failures.append(f"case {k}: the page shows links {got!r}, not {names!r}")
            if None in drawn:
                failures.append(f"case {k}: a link's box is not drawn: {dict(zip(names, drawn))}")
            if browser.console_errors():
                failures.append(f"case {k}: console errors: {browser.console_errors()[:3]}")
    except cdp.ChromiumError as e:
        failures.append(str(e))
    finally:
        if browser:
            browser.close()
    for f in failures:
        print("FAIL: " + f)
    print(f"page_names: {len(cases)} models, {len(pages)} pages, {min(6, len(pages))} in Chromium, "
          f"{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
