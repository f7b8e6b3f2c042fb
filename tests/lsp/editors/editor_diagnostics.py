#!/usr/bin/env python3
"""A real editor drives bodyls over every corpus model: its diagnostics must be bodycheck's.

usage: editor_diagnostics.py {nvim,emacs} EDITOR_PROGRAM BODYLS BODYCHECK CORPUS EDITORS_DIR WORK_DIR [--viewer]

One editor process (headless Neovim with nvim_session.lua, or batch Emacs with eglot and
eglot_session.el), set up by editors/ as a user sets it up, opens every CORPUS/choreonoid/**.body
in turn. After the model opens, after an edit that appends EDIT_LINE, and after undoing it, the
editor's diagnostics must equal `bodycheck --format json`'s findings on the same text (the edited
text through --stdin-filename) exactly: file, line, column, severity and rule, nothing missing,
nothing extra. Columns are compared in bytes, bodycheck's unit: Neovim converts the server's UTF-16
positions itself (the buffer's diagnostics), eglot places them in its buffer, and this script
converts the server's raw positions and eglot's list-only ones (files not visited) from UTF-16 on
its own, from the text. EDIT_LINE puts non-ASCII text and a surrogate pair before its finding, so
a column counted in bytes, code points or UTF-16 units differs.

Severities compare as LSP's: bodycheck's fatal and error are 1, warning 2, note 3 (or 4).
Then the editor's own keys on a small model (KEYS_MODEL): in Neovim, <C-x><C-o> completes a
key at the typed line's indentation, K shows the key's hover, and <C-]> on Tank.body's
`parent: CHASSIS` lands where go to definition does; in Emacs, eldoc shows the hover without
Markdown markup (eglot renders none without markdown-mode).
With --viewer (a build with bodyview, which bodyls runs from beside itself), the set-up's viewer
command (:BodyView, C-c C-v) then opens the first model in bodyview: its page must be served.
Prints the editor's wall time and the median time from opening a model to its diagnostics.
"""
import concurrent.futures
import glob
import json
import os
import statistics
import subprocess
import sys
import time

EDIT_LINE = "extra_\u00fc\U0001F600: {\u00e4: 1, \u00e4: 2}"
SCALE = float(os.environ.get("BODYFMT_TIME_SCALE", "1"))
SEVERITY = {"fatal": 1, "error": 1, "warning": 2, "note": 3}


def bodycheck_findings(bodycheck, path, text=None):
    cmd = [bodycheck, "--format", "json"]
    if text is None:
        run = subprocess.run(cmd + [path], capture_output=True, text=True)
    else:
        run = subprocess.run(cmd + ["--stdin-filename", path, "-"], input=text, capture_output=True, text=True)
    if run.returncode not in (0, 1):
        raise RuntimeError(f"bodycheck {path}: exit {run.returncode}: {run.stderr[-400:]}")
    return json.loads(run.stdout)["diagnostics"]


def expected_keys(findings):
    keys = []
    for d in findings:
        # A finding with no place in its file is at its start for an editor.
        line, column = (d["line"], d["column"]) if d["line"] > 0 else (1, 1)
        keys.append((os.path.realpath(d["file"]), line, max(column, 1), SEVERITY[d["severity"]], d["rule"]))
    return sorted(keys)


def counts_by_file(keys):
    counts = {}
    for k in keys:
        counts[k[0]] = counts.get(k[0], 0) + 1
    return counts


def byte_column(text, line, utf16):
    """1-based byte column of the 0-based UTF-16 offset `utf16` on 1-based `line` of `text`."""
    lines = text.split("\n")
    if not 1 <= line <= len(lines):
        return -1
    units = 0
    column = 1
    for ch in lines[line - 1]:
        if units >= utf16:
            break
        units += 2 if ord(ch) > 0xFFFF else 1
        column += len(ch.encode("utf-8"))
    return column if units >= utf16 else -1


def editor_keys(snapshot, texts):
    """(client's view, server's raw positions converted here), both as bodycheck's keys."""
    def text_of(path):
        if path not in texts:
            with open(path, encoding="utf-8", errors="replace") as f:
                texts[path] = f.read()
        return texts[path]

    shown = []
    for d in snapshot.get("diagnostics") or []:
        path = os.path.realpath(d["file"])
        if "column" in d:
            column = d["column"]
        else:  # eglot's list-only diagnostics keep the server's UTF-16 offset (1-based)
            column = byte_column(text_of(path), d["line"], d["utf16_column"] - 1)
        shown.append((path, d["line"], column, min(d["severity"] or 1, 3), d["code"]))
    raw = []
    for d in snapshot.get("raw") or []:
        path = os.path.realpath(d["file"])
        raw.append((path, d["line"] + 1, byte_column(text_of(path), d["line"] + 1, d["character"]),
                    min(d["severity"] or 1, 3), d["code"]))
    return sorted(shown), sorted(raw)


def differences(what, got, expected):
    missing = [k for k in expected if k not in got]
    extra = [k for k in got if k not in expected]
    if len(got) != len(expected) and not missing and not extra:
        return [f"{what}: {len(got)} diagnostics, {len(expected)} expected (repeated ones differ)"]
    out = [f"{what}: missing {k}" for k in missing[:5]] + [f"{what}: unexpected {k}" for k in extra[:5]]
    if len(missing) + len(extra) > 10:
        out.append(f"{what}: {len(missing)} missing and {len(extra)} unexpected in all")
    return out


def viewer_failures(viewer):
    """:BodyView (Neovim) or C-c C-v (Emacs) has bodyls open the model in bodyview: the server
    answers with the page's URL, asks the editor to show it (window/showDocument, or a message
    naming it; eglot's command opens the URL it answers itself), and the page is there."""
    if not viewer:
        return ["BodyView: no result"]
    url = viewer.get("url")
    if not url:
        return [f"BodyView: no URL ({viewer.get('error')})"]
    failures = []
    if viewer.get("shown") != url and url not in (viewer.get("message") or ""):
        failures.append(f"BodyView: the editor was not asked to show {url} (shown {viewer.get('shown')!r}, "
                        f"message {viewer.get('message')!r})")
    page = viewer.get("page") or ""
    if not page.startswith(("HTTP/1.0 200", "HTTP/1.1 200")) or "<!doctype html>" not in page.lower():
        failures.append(f"BodyView: GET {url} did not answer the page: {page[:200]!r}")
    return failures


def definition_plan(root, expected):
    """Tank.body's `parent: CHASSIS` names a link of its SubBody TankBody.body: where the editor
    must land, found here in TankBody.body's text (1-based line, 1-based byte column)."""
    tank = os.path.realpath(os.path.join(root, "Tank", "Tank.body"))
    body = os.path.realpath(os.path.join(root, "Tank", "TankBody.body"))
    if tank not in expected or not os.path.exists(body):
        return None
    def place(text, needle, shift):
        at = text.find(needle)
        if at < 0:
            return None
        start = text.rfind("\n", 0, at) + 1
        return text.count("\n", 0, at) + 1, len(text[start:at].encode("utf-8")) + shift + 1
    source = place(expected[tank]["text"], "parent: CHASSIS", len("parent: ") + 2)
    with open(body, encoding="utf-8") as f:
        target = place(f.read(), "name: CHASSIS", len("name: "))
    if not source or not target:
        return None
    return {"path": tank, "line": source[0], "column": source[1], "counts": counts_by_file(expected[tank]["opened"]),
            "expect": {"file": os.path.realpath(body), "line": target[0], "column": target[1]}}


def definition_failures(got, plan):
    if not got:
        return ["definition: no result"]
    want = plan["expect"]
    landed = {"file": os.path.realpath(got.get("file") or ""), "line": got.get("line"), "column": got.get("column")}
    return [] if landed == want else [f"definition: landed at {landed}, expected {want}"]


# A model for the editor's own keys (Neovim): the typed line below its last one completes to a
# key of ARM at ARM's indentation; K on `mass` shows the key's unit.
KEYS_MODEL = """format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
name: keys
root_link: BASE
links:
  -
    name: BASE
    joint_type: free
    mass: 2.5
    inertia: [ 1, 0, 0, 0, 1, 0, 0, 0, 1 ]
  -
    name: ARM
    parent: BASE
    joint_type: revolute
    joint_axis: Z
    joint_id: 0
    mass: 1
    inertia: [ 1, 0, 0, 0, 1, 0, 0, 0, 1 ]
"""
KEYS_TYPED = "    joint_ra"


def keys_plan(work, bodycheck):
    path = os.path.realpath(os.path.join(work, "keys.body"))
    with open(path, "w", encoding="utf-8") as f:
        f.write(KEYS_MODEL)
    lines = KEYS_MODEL.split("\n")
    hover_line = lines.index("    mass: 2.5") + 1
    return {"path": path, "counts": counts_by_file(expected_keys(bodycheck_findings(bodycheck, path))),
            "typed": KEYS_TYPED, "hover_line": hover_line, "hover_column": 5}


def keys_failures(editor, got):
    """Neovim: <C-x><C-o> completes `joint_ra` to the key joint_range at the typed line's
    indentation (Neovim 0.7's vim.lsp.buf.completion() loses it); K shows the hover of `mass`
    (kilograms), not a man page. Emacs: eldoc shows that hover as text, without the Markdown
    markup Emacs 28's eglot cannot render without markdown-mode (it asks for plain text)."""
    if not got:
        return ["keys: no result"]
    failures = []
    hover = got.get("hover") or ""
    if editor != "nvim":
        if "mass" not in hover or "kg" not in hover or "**" in hover or "`" in hover:
            failures.append(f"hover: eldoc showed {hover!r}, not the hover of `mass` (unit kg) without markup")
        return failures
    completed = (got.get("completed") or "").rstrip()
    if completed != "    joint_range:":
        failures.append(f"keys: <C-x><C-o> after {KEYS_TYPED!r} left {got.get('completed')!r}, expected "
                        f"'    joint_range: ' (error: {got.get('completion_error')})")
    if "mass" not in hover or "kg" not in hover:
        failures.append(f"keys: K on `mass` showed {hover!r}, not the key's hover with its unit kg "
                        f"(error: {got.get('hover_error')})")
    return failures


# Choreonoid's Body File Tutorial builds SimpleTank in stages: the chassis, the turret's yaw
# link, its pitch link (the turret, then the gun), the tracks, the spot light, the camera. The
# stages are cut here from the corpus's final SimpleTank.body: each adds a block to the last.
# What each stage must get, as judged by hand (rule, the text of the line it points at):
# CHASSIS's inertia diag(0.1, 0.1, 0.5) breaks the triangle inequality (0.1 + 0.1 < 0.5), and
# the tracks write the legacy `centerOfMass` in a format 2.0 file (a safe rename, which the
# editor must offer as a code action). Nothing else is wrong in the tutorial's model.
TUTORIAL_STAGES = ("chassis", "turret yaw link", "turret pitch link", "gun", "tracks", "spot light", "camera")
TUTORIAL_RIGHT = {"inertia-triangle": "    inertia: [", "load-legacy-key": "    centerOfMass: [ 0, 0, 0 ]"}


def tutorial_texts(root):
    with open(os.path.join(root, "Tank", "SimpleTank.body"), encoding="utf-8") as f:
        lines = f.read().rstrip("\n").split("\n")
    link = {lines[i + 1].split(": ")[1].strip(): i for i in range(len(lines) - 1)
            if lines[i].strip() == "-" and lines[i + 1].startswith("    name: ")}
    item = {}  # the TURRET_P element items: the line of the `-` before the comment or type
    for i, line in enumerate(lines):
        for name, mark in (("gun", "# Gun"), ("light", "type: SpotLight"), ("camera", "type: Camera")):
            if line.strip() == mark:
                item[name] = i - 1
    end = len(lines)

    def without(*ranges):
        return "\n".join(l for i, l in enumerate(lines) if not any(a <= i < b for a, b in ranges)) + "\n"
    tracks = (link["TRACK_L"], end)
    return [without((link["TURRET_Y"], end)), without((link["TURRET_P"], end)),
            without((item["gun"], link["TRACK_L"]), tracks), without((item["light"], link["TRACK_L"]), tracks),
            without((item["light"], link["TRACK_L"])), without((item["camera"], link["TRACK_L"])),
            "\n".join(lines) + "\n"]


def tutorial_failures(texts, findings):
    """bodycheck's findings on each stage are the judged ones (TUTORIAL_RIGHT), no more."""
    failures = []
    for n, (text, found) in enumerate(zip(texts, findings)):
        lines = text.split("\n")
        wrong = [f for f in found if not (f["rule"] in TUTORIAL_RIGHT and 0 < f["line"] <= len(lines)
                                          and lines[f["line"] - 1].startswith(TUTORIAL_RIGHT[f["rule"]]))]
        failures += [f"tutorial stage {n + 1} ({TUTORIAL_STAGES[n]}): a wrong finding {f['line']}:{f['column']} "
                     f"[{f['rule']}] {f['message'][:100]}" for f in wrong]
        rules = sorted(f["rule"] for f in found)
        want = ["inertia-triangle"] + (["load-legacy-key"] * 2 if n >= 4 else [])
        if rules != sorted(want):
            failures.append(f"tutorial stage {n + 1} ({TUTORIAL_STAGES[n]}): findings {rules}, expected {sorted(want)}")
    return failures


def stage_action_failures(editor, stages):
    """Each stage's diagnostics offer the actions that exist: the legacy key's rename, and for
    CHASSIS's impossible inertia the one that computes it from the chassis's box."""
    failures = []
    for n, entry in enumerate(stages or []):
        codes = set()
        for a in entry.get("actions") or []:
            codes.add(a.get("code"))
            if a.get("code") == "load-legacy-key" and not a.get("titles"):
                failures.append(f"tutorial stage {n + 1} ({editor}): no code action on the legacy key at line {a['line']}")
            if a.get("code") == "inertia-triangle" and not any(
                    'inertia of link "CHASSIS" from its shapes' in t for t in a.get("titles") or []):
                failures.append(f"tutorial stage {n + 1} ({editor}): no action computing CHASSIS's inertia from its "
                                f"shapes at line {a['line']}: {a.get('titles')}")
        if stages and "inertia-triangle" not in codes:
            failures.append(f"tutorial stage {n + 1} ({editor}): no code actions were asked for on the inertia finding")
    return failures


def run_editor(editor, program, plan_path, result_path, work, here):
    env = dict(os.environ, BODYLS_PLAN=plan_path, BODYLS_RESULT=result_path, HOME=work, XDG_CONFIG_HOME=work,
               XDG_DATA_HOME=work, XDG_STATE_HOME=work, XDG_CACHE_HOME=work)
    if editor == "nvim":
        cmd = [program, "--headless", "-u", "NONE", "-i", "NONE", "-n",
               "-c", "luafile " + os.path.join(here, "nvim_session.lua")]
    else:
        cmd = [program, "--batch", "-l", os.path.join(here, "eglot_session.el")]
    started = time.monotonic()
    run = subprocess.run(cmd, env=env, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                         timeout=300 * SCALE)
    return time.monotonic() - started, run


def main():
    editor, program, server, bodycheck, corpus, editors_dir, work = sys.argv[1:8]
    if not os.access(program, os.X_OK):
        print(f"FAIL: {editor} is not installed ({program}): README.md's install command installs it")
        return 1
    here = os.path.dirname(os.path.abspath(__file__))
    work = os.path.abspath(work)
    os.makedirs(work, exist_ok=True)
    root = os.path.realpath(os.path.join(corpus, "choreonoid"))
    models = sorted(os.path.realpath(p) for p in glob.glob(os.path.join(root, "**", "*.body"), recursive=True))
    if not models:
        print(f"FAIL: no models under {root}")
        return 1

    def expectations(path):
        with open(path, encoding="utf-8") as f:
            text = f.read()
        edited = (text if text.endswith("\n") or not text else text + "\n") + EDIT_LINE + "\n"
        return path, text, edited, expected_keys(bodycheck_findings(bodycheck, path)), \
            expected_keys(bodycheck_findings(bodycheck, path, edited))

    expected = {}
    plan_models = []
    failures = []
    with concurrent.futures.ThreadPoolExecutor(2) as pool:  # CI's two cores
        found = list(pool.map(expectations, models))
    for path, text, edited, opened, after_edit in found:
        if not set(after_edit) - set(opened):
            failures.append(f"{path}: the edit adds no finding for bodycheck: the edit checks nothing")
        expected[path] = {"text": text, "edited": edited, "opened": opened, "edited_keys": after_edit}
        plan_models.append({"path": path, "opened": counts_by_file(opened), "edited": counts_by_file(after_edit)})

    plan = {"server": os.path.abspath(server), "editors_dir": os.path.abspath(editors_dir), "root_dir": root,
            "timeout_ms": int(10000 * SCALE), "edit_line": EDIT_LINE, "models": plan_models}
    definition = None
    if editor == "nvim":
        definition = definition_plan(root, expected)
        if definition:
            plan["definition"] = definition
        else:
            failures.append("no Tank/Tank.body with `parent: CHASSIS` in the corpus for go to definition")
    plan["keys"] = keys_plan(work, bodycheck)
    stage_texts = tutorial_texts(root)
    stage_path = os.path.realpath(os.path.join(work, "tutorial", "SimpleTank.body"))
    os.makedirs(os.path.dirname(stage_path), exist_ok=True)
    open(stage_path, "w").close()  # the user's new, empty file
    stage_findings = [bodycheck_findings(bodycheck, stage_path, t) for t in stage_texts]
    failures += tutorial_failures(stage_texts, stage_findings)
    plan["stages"] = {"path": stage_path, "steps": [{"text": t, "counts": counts_by_file(expected_keys(f))}
                                                    for t, f in zip(stage_texts, stage_findings)]}
    viewer = "--viewer" in sys.argv[8:]
    if viewer:
        plan["viewer"] = models[0]
    plan_path = os.path.join(work, f"{editor}_plan.json")
    result_path = os.path.join(work, f"{editor}_result.json")
    with open(plan_path, "w", encoding="utf-8") as f:
        json.dump(plan, f, ensure_ascii=False)
    if os.path.exists(result_path):
        os.remove(result_path)
    seconds, run = run_editor(editor, program, plan_path, result_path, work, here)
    if not os.path.exists(result_path):
        print(f"FAIL: {editor} wrote no result (exit {run.returncode}):\n{run.stdout[-1500:]}\n{run.stderr[-1500:]}")
        return 1
    with open(result_path, encoding="utf-8") as f:
        result = json.load(f)
    if result.get("error"):
        failures.append(f"{editor}: {result['error']}")
    failures += [f"{editor}: {note}" for note in result.get("notes") or []]
    done = result.get("models") or []
    if len(done) != len(models):
        failures.append(f"{editor} went through {len(done)} of {len(models)} models")

    open_ms = []
    for entry in done:
        path = os.path.realpath(entry["path"])
        want = expected[path]
        name = os.path.relpath(path, root)
        open_ms.append(entry.get("open_ms") or 0)
        for step, text, keys in (("opened", want["text"], want["opened"]),
                                 ("edited", want["edited"], want["edited_keys"]),
                                 ("undone", want["text"], want["opened"])):
            if step not in entry:
                failures.append(f"{name}: no {step} step")
                continue
            shown, raw = editor_keys(entry[step], {path: text})
            failures += differences(f"{name} {step} ({editor})", shown, keys)
            failures += differences(f"{name} {step} (server's positions from UTF-16)", raw, keys)

    if definition:
        failures += definition_failures(result.get("definition"), definition)
        failures += ["<C-]>: " + f for f in definition_failures(result.get("tag_definition"), definition)]
    failures += keys_failures(editor, result.get("keys"))
    got_stages = result.get("stages") or []
    if len(got_stages) != len(stage_texts):
        failures.append(f"{editor} typed {len(got_stages)} of {len(stage_texts)} tutorial stages")
    for n, (entry, text, found) in enumerate(zip(got_stages, stage_texts, stage_findings)):
        shown, raw = editor_keys(entry.get("shown") or {}, {stage_path: text})
        failures += differences(f"tutorial stage {n + 1} ({editor})", shown, expected_keys(found))
    failures += stage_action_failures(editor, got_stages)
    if viewer:
        failures += viewer_failures(result.get("viewer"))

    for f in failures:
        print("FAIL: " + f)
    median = statistics.median(open_ms) if open_ms else 0
    print(f"{editor}: {len(done)}/{len(models)} models, 3 steps each, {seconds:.1f} s in the editor "
          f"(open to diagnostics: median {median:.0f} ms), " + ("FAIL" if failures else "OK"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
