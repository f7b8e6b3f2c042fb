#!/usr/bin/env python3
"""Runs every tool on one hostile input and checks the robustness contract.

    run_case.py CASE BIN_DIR

CASE is a .body file (or a folder holding main.body) under tests/data/hostile, or one that
tests/hostile/generate.py wrote; or a .urdf file, which urdf2body imports (urdf_case): what it
writes must load back in bodycheck without an error (issue 34). Its comment lines (or, for a file that cannot hold comments,
such as an empty or a binary one, the lines of CASE.expect beside it) say what each tool must
do:

    # expect: bodycheck exit=1 rule=joint-id-gap
    # expect: bodyinfo exit=0
    # limit: cpu=20


Every tool named in the file must exit with that code within the time limit, without a
signal, and print each listed rule id in a located diagnostic (`file:line:col: ... [rule]`).
Tools the file does not name must still not crash or hang (exit 0, 1 or 2). `# limit: cpu=N`
raises the CPU seconds each tool may take (the 100,000-link models, whose export builds a
scene of 400,000 nodes). bodydiff runs too, its expectations derived from bodycheck's
(bodydiff_runs). On the cases kept in the repository, bodyview's page keeps the model's text
inside its data <script> (page_runs), and, on a case bodycheck can load, git diff works through
both set-ups docs/tools/bodydiff.md gives, with the case's own file name (git_driver_runs).
"""
import json
import os
import re
import resource
import subprocess
import sys
import tempfile

TOOLS = ["bodyinfo", "bodycheck", "body2urdf", "body2mjcf", "body2gltf", "bodysim"]
# "Within a few seconds": CPU seconds per tool run, so that a loaded machine does not fail a
# fast tool; the wall-clock limit only catches hangs. Sanitizer builds run several times
# slower: tests/fuzz/run.sh scales both with BODYFMT_TIME_SCALE.
SCALE = float(os.environ.get("BODYFMT_TIME_SCALE", "1"))
CPU_LIMIT = 10 * SCALE
WALL_LIMIT = 120 * SCALE


# At a line and column, or at the file for what has none (a binary file, an empty one).
LOCATED_ERROR = re.compile(r"^\S+?(:\d+:\d+)?: (error|fatal error): .*\[[a-z0-9-]+\]$", re.M)


def run_tool(what, argv, cpu_limit, failures):
    """Runs one tool; returns (exit code, output) or None after a hang or a crash, which it
    records in `failures` with its CPU time when over the limit."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    try:
        run = subprocess.run(argv, capture_output=True, timeout=WALL_LIMIT)
    except subprocess.TimeoutExpired:
        failures.append(f"{what}: no answer within {WALL_LIMIT:g} s")
        return None
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if cpu > cpu_limit:
        failures.append(f"{what}: {cpu:.1f} CPU seconds, over the limit of {cpu_limit:g}")
    text = (run.stdout + run.stderr).decode("utf-8", "replace")
    if run.returncode < 0 or run.returncode not in (0, 1, 2):
        failures.append(f"{what}: exit {run.returncode} (a crash)\n{text[-2000:]}")
        return None
    return run.returncode, text


def check_rules(what, text, rules, failures):
    """Each rule must appear in a located diagnostic: `file:line:col: severity: ... [rule]`."""
    for rule in rules:
        if not re.search(r"^\S+:\d+:\d+: [a-z ]+: .*\[" + re.escape(rule) + r"\]$", text, re.M):
            failures.append(f"{what}: no located [{rule}] diagnostic\n{text[-2000:]}")


def bodydiff_runs(bin_dir, model, expectations, cpu_limit):
    """bodydiff (issue 28) on the same cases: the model against itself (text and JSON), and
    --textconv. A model bodycheck cannot load (its exit 2) stops bodydiff
    with exit 2 and a located error, naming every rule the case expects of bodycheck; any other
    model is the same as itself: exit 0, nothing printed. --textconv prints the model or stops
    the same way. A `# expect: bodydiff ...` line in the case overrides the first rule."""
    failures = []
    check = expectations.get("bodycheck")
    expect = expectations.get("bodydiff")
    if expect is None and check is not None:
        expect = {"exit": "2", "rules": check["rules"]} if check.get("exit") == "2" else {"exit": "0", "rules": []}
    for args in ([model, model], ["--textconv", model], ["--format", "json", model, model]):
        what = "bodydiff " + " ".join(a if a != model else "MODEL" for a in args)
        result = run_tool(what, [os.path.join(bin_dir, "bodydiff"), *args], cpu_limit, failures)
        if result is None or expect is None:
            continue
        code, text = result
        if code != 2 and code != int(expect["exit"]) and args[0] != "--textconv":
            failures.append(f"{what}: exit {code}, expected {expect['exit']}\n{text[-2000:]}")
            continue
        if expect["exit"] == "2":
            if code != 2:
                failures.append(f"{what}: exit {code}, expected 2\n{text[-2000:]}")
            elif not LOCATED_ERROR.search(text):
                failures.append(f"{what}: no located error\n{text[-2000:]}")
            check_rules(what, text, expect["rules"], failures)
        elif code != 0:
            failures.append(f"{what}: exit {code}, expected 0\n{text[-2000:]}")
        elif args[0] != "--textconv" and args[0] != "--format" and text:
            failures.append(f"{what}: a model differs from itself\n{text[-2000:]}")
        elif args[0] == "--format" and '"changes": []' not in text:
            failures.append(f"{what}: a model differs from itself\n{text[-2000:]}")
    return failures


FORBIDDEN_IN_DATA = ["<", ">", "&", "\u2028", "\u2029"]
BODYDIFF_MANUAL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "tools", "bodydiff.md")
SMALL = 1 << 20  # the page and git checks run on the cases kept in the repository, not the generated giants


def page_runs(bin_dir, model, out, cpu_limit, expect):
    """bodyview (issue 34): a page it writes carries the model's text in a data <script> that
    holds no character the HTML tokenizer reads there, and whose JSON parses."""
    failures = []
    if not os.access(os.path.join(bin_dir, "bodyview"), os.X_OK):
        return failures  # bodyview is optional (no three.js at configure time)
    page = os.path.join(out, "page.html")
    result = run_tool("bodyview", [os.path.join(bin_dir, "bodyview"), model, "-q", "-o", page], cpu_limit, failures)
    if result is not None and expect and str(result[0]) != expect.get("exit"):
        failures.append(f"bodyview: exit {result[0]}, expected {expect.get('exit')}\n{result[1][-2000:]}")
    if result is None or result[0] == 2:
        return failures
    with open(page, encoding="utf-8", errors="replace") as f:
        html = f.read()
    opening = '<script type="application/json" id="bv-data">'
    start = html.index(opening) + len(opening)
    data = html[start:re.compile(r"</script", re.I).search(html, start).start()]
    found = [c for c in FORBIDDEN_IN_DATA if c in data]
    if found:
        failures.append(f"bodyview: the page's data <script> holds {found}")
    try:
        json.loads(data)
    except ValueError as e:
        failures.append(f"bodyview: the page's data <script> is not its JSON: {e}")
    return failures


def git_driver_runs(bin_dir, model, out):
    """The git diff set-ups of bodydiff's manual (docs/tools/bodydiff.md), word for word, on the case staged under its own name
    as a new file: git diff --cached exits 0 through both, whatever the name."""
    failures = []
    lines = open(BODYDIFF_MANUAL, encoding="utf-8").read().splitlines()
    configs = dict(re.findall(r'^git config (diff\.body\.\w+) "bodydiff (.*)"$', "\n".join(lines), re.M))
    if set(configs) != {"diff.body.textconv", "diff.body.command"}:
        return [f"docs/tools/bodydiff.md gives no git diff set-up: {configs}"]
    repo = os.path.join(out, "repo")
    name = os.path.basename(model)
    env = dict(os.environ, GIT_CONFIG_NOSYSTEM="1", HOME=out, GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@example.com",
               GIT_COMMITTER_NAME="t", GIT_COMMITTER_EMAIL="t@example.com")
    git = lambda *args: subprocess.run(["git", *args], cwd=repo, env=env, capture_output=True, timeout=WALL_LIMIT)
    os.makedirs(repo)
    git("init", "-q")
    with open(os.path.join(repo, ".gitattributes"), "w") as f:
        f.write("*.body diff=body\n")
    with open(model, "rb") as f, open(os.path.join(repo, name), "wb") as g:
        g.write(f.read())
    git("add", "--", ".gitattributes")
    git("commit", "-qm", "attributes")
    git("add", "--", name)  # a new file: the drivers get its name and its text as it is
    bodydiff = os.path.join(bin_dir, "bodydiff")
    for key, args in sorted(configs.items()):
        run = git("-c", f"{key}='{bodydiff}' {args}", "diff", "--cached")
        if run.returncode != 0:
            failures.append(f"git diff with {key} as docs/tools/bodydiff.md gives it: exit {run.returncode}\n"
                            f"{run.stderr.decode('utf-8', 'replace')[-1000:]}")
    return failures


def urdf_case(bin_dir, case, expectations, cpu_limit):
    """urdf2body on a URDF case; a .body it writes must load in bodycheck without an error
    (a URDF link without <inertial> is massless, which bodycheck's mass rule would report)."""
    failures = []
    with tempfile.TemporaryDirectory() as out:
        written = os.path.join(out, "out.body")
        result = run_tool("urdf2body", [os.path.join(bin_dir, "urdf2body"), case, "-o", written], cpu_limit, failures)
        expect = expectations.get("urdf2body")
        if result is not None and expect is not None:
            code, text = result
            if str(code) != expect.get("exit"):
                failures.append(f"urdf2body: exit {code}, expected {expect.get('exit')}\n{text[-2000:]}")
            check_rules("urdf2body", text, expect["rules"], failures)
            if code == 2 and not LOCATED_ERROR.search(text):
                failures.append(f"urdf2body: no located error\n{text[-2000:]}")
        if os.path.exists(written):
            check = run_tool("bodycheck", [os.path.join(bin_dir, "bodycheck"), "--disable", "inertia-nonpositive-mass",
                                            written], cpu_limit, failures)
            if check is not None and (check[0] == 2 or re.search(r": (error|fatal error): ", check[1])):
                failures.append(f"bodycheck on what urdf2body wrote: exit {check[0]}\n{check[1][-2000:]}")
    return failures


def main():
    case, bin_dir = sys.argv[1], sys.argv[2]
    model = os.path.join(case, "main.body") if os.path.isdir(case) else case
    sidecar = case + ".expect"
    with open(sidecar if os.path.exists(sidecar) else model, "rb") as f:
        head = f.read(4096).decode("utf-8", "replace")
    expectations = {}
    for tool, spec in re.findall(r"^# expect: (\S+) (.*)$", head, re.M):
        expectations[tool] = dict(kv.split("=", 1) for kv in spec.split())
        expectations[tool]["rules"] = re.findall(r"rule=(\S+)", spec)
    cpu_limit = CPU_LIMIT
    for value in re.findall(r"^# limit: cpu=(\S+)$", head, re.M):
        cpu_limit = float(value) * SCALE
    if case.endswith(".urdf"):
        failures = urdf_case(bin_dir, case, expectations, cpu_limit)
        for f in failures:
            print(f)
        print(f"{os.path.basename(case)}: urdf2body, {len(failures)} failures")
        return 1 if failures else 0
    failures = []
    with tempfile.TemporaryDirectory() as out:
        for tool in TOOLS:
            args = [os.path.join(bin_dir, tool), model]
            if tool == "bodysim":
                args = [os.path.join(bin_dir, tool), "check", model]  # the generic dynamics checks
            if tool.startswith("body2"):
                extension = {"body2gltf": "glb"}.get(tool, tool[len("body2"):])
                args += ["-o", os.path.join(out, "out." + extension)]
            result = run_tool(tool, args, cpu_limit, failures)
            expect = expectations.get(tool)
            if result is None or expect is None:
                continue
            code, text = result
            if str(code) != expect.get("exit"):
                failures.append(f"{tool}: exit {code}, expected {expect.get('exit')}\n{text[-2000:]}")
            check_rules(tool, text, expect["rules"], failures)
        failures += bodydiff_runs(bin_dir, model, expectations, cpu_limit)
        if os.path.getsize(model) < SMALL:
            failures += page_runs(bin_dir, model, out, cpu_limit, expectations.get("bodyview"))
            if expectations.get("bodycheck", {}).get("exit") in ("0", "1") and not os.path.isdir(case):
                failures += git_driver_runs(bin_dir, model, out)
    for f in failures:
        print(f)
    print(f"{os.path.basename(case)}: {len(TOOLS) + 1} tools, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
