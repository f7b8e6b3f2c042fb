#!/usr/bin/env python3
"""bodydiff's JSON output against the JSON Schemas in docs/: bodydiff.schema.json for one pair
(and each file of --git-rev), bodydiff-git-rev.schema.json for --git-rev and --staged (an array).

usage: bodydiff_schema.py BODYDIFF DOCS_DIR MODEL WORK_DIR   (MODEL: SR1.body, with WAIST_P's mass 6.0)

The outputs validated: two models the same, a mass change, and in a scratch git repository
--git-rev HEAD and --staged over a changed, an unchanged and a new model. Beside the schemas, the
summaries must count the changes, and --git-rev must name the sides REV:PATH and PATH. Mutants
of real outputs (a key missing, a wrong kind, a changed value with no old side, one document
where an array belongs, and the reverse) must be rejected, so that the schemas are not vacuous.
"""
import copy
import json
import os
import shutil
import subprocess
import sys

import jsonschema
from referencing import Registry, Resource


def main():
    bodydiff, docs, model, work = sys.argv[1:5]
    bodydiff = os.path.abspath(bodydiff)
    one = json.load(open(os.path.join(docs, "bodydiff.schema.json")))
    many = json.load(open(os.path.join(docs, "bodydiff-git-rev.schema.json")))
    for schema in (one, many):
        jsonschema.Draft202012Validator.check_schema(schema)
    registry = Registry().with_resource(one["$id"], Resource.from_contents(one))
    validators = {"one": jsonschema.Draft202012Validator(one, registry=registry),
                  "many": jsonschema.Draft202012Validator(many, registry=registry)}
    failures = []

    def check(what, output, kind):
        errors = sorted(validators[kind].iter_errors(output), key=str)
        if errors:
            failures.append(f"{what}: {errors[0].message} at {list(errors[0].absolute_path)}")
        for doc in output if kind == "many" else [output]:
            kinds = [c["kind"] for c in doc["changes"]]
            expected = {"changes": len(kinds), **{k: kinds.count(k) for k in ("added", "removed", "changed")}}
            if doc["summary"] != expected:
                failures.append(f"{what}: summary {doc['summary']}, the changes count {expected}")

    def run(args, expected_code, cwd=None):
        r = subprocess.run([bodydiff, "--format", "json", *args], capture_output=True, text=True, cwd=cwd)
        if r.returncode != expected_code:
            failures.append(f"{args}: exit {r.returncode}, not {expected_code}: {r.stderr}")
        return json.loads(r.stdout)

    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    text = open(model, encoding="utf-8").read()
    assert "    mass: 6.0\n" in text
    heavier = text.replace("    mass: 6.0\n", "    mass: 8.5\n", 1)
    old, new = os.path.join(work, "old.body"), os.path.join(work, "new.body")
    open(old, "w").write(text)
    open(new, "w").write(heavier)

    same = run([old, old], 0)
    check("the same model", same, "one")
    if same["changes"]:
        failures.append("the same model: changes listed")
    changed = run([old, new], 1)
    check("a mass change", changed, "one")

    # --git-rev and --staged in a scratch repository.
    repo = os.path.join(work, "repo")
    os.makedirs(repo)
    env = dict(os.environ, GIT_CONFIG_NOSYSTEM="1", HOME=work, GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@example.com",
               GIT_COMMITTER_NAME="t", GIT_COMMITTER_EMAIL="t@example.com")
    for k in ("GIT_DIR", "GIT_WORK_TREE", "GIT_INDEX_FILE"):
        env.pop(k, None)

    def git(*args):
        subprocess.run(["git", *args], cwd=repo, env=env, check=True, capture_output=True)

    git("init", "-q", ".")
    for name in ("robot.body", "same.body"):
        open(os.path.join(repo, name), "w").write(text)
    git("add", ".")
    git("commit", "-qm", "init")
    open(os.path.join(repo, "robot.body"), "w").write(heavier)
    open(os.path.join(repo, "arm.body"), "w").write(text)
    files = ["robot.body", "same.body", "arm.body"]
    r = subprocess.run([bodydiff, "--format", "json", "--git-rev", "HEAD", *files], capture_output=True, text=True,
                       cwd=repo, env=env)
    if r.returncode != 1:
        failures.append(f"--git-rev: exit {r.returncode}: {r.stderr}")
    revs = json.loads(r.stdout)
    check("--git-rev", revs, "many")
    if [(d["old"], d["new"]) for d in revs] != [(f"HEAD:{f}", f) for f in files]:
        failures.append(f"--git-rev sides: {[(d['old'], d['new']) for d in revs]}")
    elif revs[1]["changes"] or not revs[0]["changes"] or {c["kind"] for c in revs[2]["changes"]} != {"added"}:
        failures.append("--git-rev: not (changed, same, all added)")
    git("add", "robot.body", "arm.body")
    r = subprocess.run([bodydiff, "--format", "json", "--staged", *files], capture_output=True, text=True, cwd=repo,
                       env=env)
    if r.returncode != 0:
        failures.append(f"--staged: exit {r.returncode}: {r.stderr}")
    staged = json.loads(r.stdout)
    check("--staged", staged, "many")
    if [d["changes"] for d in staged] != [d["changes"] for d in revs]:
        failures.append("--staged and --git-rev HEAD differ on the same staged files")

    # Mutants: each must be rejected.
    mutants = []
    m = copy.deepcopy(changed); del m["changes"][0]["field"]; mutants.append(("a change without field", m, "one"))
    m = copy.deepcopy(changed); m["changes"][0]["kind"] = "moved"; mutants.append(("kind moved", m, "one"))
    m = copy.deepcopy(changed); m["changes"][0]["old"] = None; mutants.append(("a change with no old side", m, "one"))
    m = copy.deepcopy(changed); m["changes"][0]["new"]["line"] = "54"; mutants.append(("a line as text", m, "one"))
    m = copy.deepcopy(changed); del m["summary"]; mutants.append(("no summary", m, "one"))
    m = copy.deepcopy(changed); m["version"] = 2; mutants.append(("version 2", m, "one"))
    mutants.append(("one document as --git-rev's", changed, "many"))
    mutants.append(("--git-rev's array as one document", revs, "one"))
    m = copy.deepcopy(revs); m[2]["changes"][0]["new"] = None; mutants.append(("an added change with no new side", m, "many"))
    for what, doc, kind in mutants:
        if validators[kind].is_valid(doc):
            failures.append(f"mutant accepted: {what}")
    print(f"5 outputs validated, {len(mutants)} mutants, {len(failures)} failures")
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
