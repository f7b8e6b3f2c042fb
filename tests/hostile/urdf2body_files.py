#!/usr/bin/env python3
"""Files read, copied and written that must not be (issue 34), from the command line:

1. urdf2body --copy-meshes copies only meshes inside the URDF's folder tree (its package) or the
   package a package:// URI names, and only files the mesh importer reads: an absolute path,
   "../..", package://pkg/../.., file://, a link out of the tree, a FIFO, a file that is no mesh
   are each a located error, and nothing is copied or written;
2. urdf2body -o onto a mesh the URDF uses is refused (also without --copy-meshes);
3. every tool that writes refuses to write over the file its standard input is;
4. the file name in the header comment cannot add lines (keys) to the model;
9/10. bodydiff --git and urdf2body --copy-meshes go through the bounded reader: /dev/zero, a
   FIFO, a 300 MB and a 5 GB (sparse) file are refused with exit 2, never std::bad_alloc;
16. names with C1 controls, NEL, U+2028, U+FFFE and U+FFFF come back from urdf2body byte for byte;
17. a mesh URI kept as written (--no-meshes) is one the .body loader takes.

    urdf2body_files.py BIN_DIR SOURCE_DIR
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

import yaml

BIN = sys.argv[1]
SOURCE = sys.argv[2]
TIMEOUT = 60 * float(os.environ.get("BODYFMT_TIME_SCALE", "1"))
STL = ("solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
       "endloop\nendfacet\nendsolid t\n")
failures = []


def run(args, cwd, stdin=None):
    """Runs a tool; returns (exit code, output). A crash or a hang is a failure (exit None)."""
    try:
        with open(stdin, "rb") if stdin else open(os.devnull, "rb") as inp:
            r = subprocess.run([os.path.join(BIN, args[0])] + args[1:], cwd=cwd, stdin=inp, capture_output=True,
                               timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        failures.append(f"{' '.join(args)}: no answer within {TIMEOUT:g} s")
        return None, ""
    text = (r.stdout + r.stderr).decode("utf-8", "replace")
    if r.returncode not in (0, 1, 2):
        failures.append(f"{' '.join(args)}: exit {r.returncode} (a crash)\n{text[-1500:]}")
        return None, text
    return r.returncode, text


def expect(what, ok, text=""):
    if not ok:
        failures.append(f"{what}\n{text[-1500:]}")


def urdf(mesh):
    return (f'<robot name="r">\n  <link name="a">\n    <visual><geometry><mesh filename="{mesh}"/></geometry></visual>\n'
            '  </link>\n</robot>\n')


def copy_meshes(root):
    """Items 1 and 10."""
    ws = os.path.join(root, "ws")
    pkg = os.path.join(ws, "pkg")
    for d in ("urdf", "meshes"):
        os.makedirs(os.path.join(pkg, d))
    with open(os.path.join(pkg, "package.xml"), "w") as f:
        f.write("<package><name>pkg</name></package>\n")
    with open(os.path.join(pkg, "meshes", "ok.stl"), "w") as f:
        f.write(STL)
    with open(os.path.join(root, "secret.stl"), "w") as f:  # a readable mesh outside the package
        f.write(STL)
    with open(os.path.join(pkg, "meshes", "notes.stl"), "w") as f:
        f.write("not a mesh\n")
    os.symlink(os.path.join(root, "secret.stl"), os.path.join(pkg, "meshes", "link.stl"))
    os.mkfifo(os.path.join(pkg, "meshes", "fifo.stl"))
    for name, size in (("big.stl", 300 << 20), ("huge.stl", 5 << 30)):  # sparse: no disk used
        with open(os.path.join(pkg, "meshes", name), "wb") as f:
            f.truncate(size)
    cases = {
        "absolute": os.path.join(root, "secret.stl"),
        "dotdot": "../../../secret.stl",
        "package_dotdot": "package://pkg/../../secret.stl",
        "file_uri": "file://" + os.path.join(root, "secret.stl"),
        "symlink_out": "package://pkg/meshes/link.stl",
        "not_a_mesh": "../meshes/notes.stl",
        "fifo": "../meshes/fifo.stl",
        "size_300MB": "../meshes/big.stl",
        "size_5GB": "package://pkg/meshes/huge.stl",
    }
    for case, mesh in cases.items():
        source = os.path.join(pkg, "urdf", case + ".urdf")
        with open(source, "w") as f:
            f.write(urdf(mesh))
        out = os.path.join(root, "out_" + case)
        os.makedirs(out)
        code, text = run(["urdf2body", source, "-o", os.path.join(out, "r.body"), "--copy-meshes"], root)
        if code is None:
            continue
        expect(f"--copy-meshes {case} ({mesh}): exit {code}, expected 2", code == 2, text)
        expect(f"--copy-meshes {case}: no error located at the mesh's line 3",
               re.search(r"\.urdf:3:\d+: (error|fatal error): ", text), text)
        expect(f"--copy-meshes {case}: something was written: {os.listdir(out)}", not os.listdir(out))
    # Inside the package, a mesh the importer reads: copied.
    source = os.path.join(pkg, "urdf", "inside.urdf")
    with open(source, "w") as f:
        f.write(urdf("package://pkg/meshes/ok.stl"))
    code, text = run(["urdf2body", source, "-o", os.path.join(root, "inside", "r.body"), "--copy-meshes"], root)
    expect(f"--copy-meshes of a mesh inside the package: exit {code}", code == 0, text)
    expect("--copy-meshes: the mesh inside was not copied",
           os.path.exists(os.path.join(root, "inside", "meshes", "r", "ok.stl")))


def unknown_scheme_kept(root):
    """Found by fuzz_urdf_import: with --no-meshes a URI is kept as written, so a scheme the
    .body loader refuses ("meshes/a://b") is an error at its line, not a file that fails to load."""
    with open(os.path.join(root, "r.urdf"), "w") as f:
        f.write(urdf("meshes/a://b.stl"))
    code, text = run(["urdf2body", "--no-meshes", "r.urdf", "-o", "r.body"], root)
    expect(f"urdf2body --no-meshes with meshes/a://b.stl: exit {code}, expected 2", code == 2, text)
    expect("urdf2body --no-meshes with meshes/a://b.stl: no error at line 3", re.search(r"r\.urdf:3:\d+: ", text), text)
    expect("urdf2body --no-meshes with meshes/a://b.stl: written", not os.path.exists(os.path.join(root, "r.body")))


def output_onto_mesh(root):
    """Item 2."""
    os.makedirs(os.path.join(root, "m"))
    with open(os.path.join(root, "m", "part.stl"), "w") as f:
        f.write(STL)
    with open(os.path.join(root, "m", "r.urdf"), "w") as f:
        f.write(urdf("part.stl"))
    code, text = run(["urdf2body", "r.urdf", "-o", "part.stl"], os.path.join(root, "m"))
    expect(f"urdf2body -o onto its mesh: exit {code}, expected 2", code == 2, text)
    with open(os.path.join(root, "m", "part.stl")) as f:
        expect("urdf2body -o onto its mesh: the mesh was written over", f.read() == STL)


def standard_input(root):
    """Item 3: the output is the file standard input reads."""
    d = os.path.join(root, "stdin")
    os.makedirs(d)
    model = os.path.join(SOURCE, "examples", "arm.body")
    scenario = os.path.join(d, "s.scenario.yaml")
    with open(scenario, "w") as f:
        f.write("duration: 0.01\n")
    with open(os.path.join(d, "r.urdf"), "w") as f:
        f.write('<robot name="r">\n  <link name="a"/>\n</robot>\n')
    runs = [
        (["bodyview", "-", "-o", "m.body"], "m.body"),
        (["body2urdf", "-", "-o", "m.body"], "m.body"),
        (["body2mjcf", "-", "-o", "m.body"], "m.body"),
        (["body2gltf", "-", "-o", "m.body"], "m.body"),
        (["bodycheck", "-", "-o", "m.body"], "m.body"),
        (["bodysim", "run", "-", "--scenario", scenario, "--csv", "m.body"], "m.body"),
        (["urdf2body", "-", "-o", "r.urdf"], "r.urdf"),
    ]
    for args, target in runs:
        if target == "m.body":
            shutil.copy(model, os.path.join(d, "m.body"))
        path = os.path.join(d, target)
        with open(path, "rb") as f:
            before = f.read()
        code, text = run(args, d, stdin=path)
        if code is None:
            continue
        with open(path, "rb") as f:
            after = f.read()
        expect(f"{' '.join(args)} < {target}: exit {code}, expected 2", code == 2, text)
        expect(f"{' '.join(args)} < {target}: the file it reads was written over", before == after)
    # Standard input from another file: written as before.
    code, text = run(["body2urdf", "-", "-o", "other.urdf"], d, stdin=model)
    expect(f"body2urdf - -o other.urdf < arm.body: exit {code}", code in (0, 1) and os.path.exists(
        os.path.join(d, "other.urdf")), text)


def header_comment(root):
    """Item 4: a newline in the name for standard input stays in the comment."""
    d = os.path.join(root, "comment")
    os.makedirs(d)
    with open(os.path.join(d, "r.urdf"), "w") as f:
        f.write('<robot name="r">\n  <link name="a"/>\n</robot>\n')
    code, text = run(["urdf2body", "-", "--stdin-filename", "x.urdf\nname: injected\nroot_link: zz", "-o", "out.body"],
                     d, stdin=os.path.join(d, "r.urdf"))
    expect(f"urdf2body --stdin-filename with a newline: exit {code}", code == 0, text)
    if code == 0:
        with open(os.path.join(d, "out.body"), encoding="utf-8") as f:
            lines = f.read().split("\n")
        expect(f"the header comment is more than one line: {lines[:3]}",
               lines[0].startswith("# ") and lines[1] == "format: ChoreonoidBody")


def bounded_reads(root):
    """Items 9 and 10: bodydiff --git on /dev/zero, a FIFO and a 300 MB file."""
    d = os.path.join(root, "git")
    os.makedirs(d)
    shutil.copy(os.path.join(SOURCE, "examples", "arm.body"), os.path.join(d, "m.body"))
    os.mkfifo(os.path.join(d, "fifo"))
    with open(os.path.join(d, "big"), "wb") as f:
        f.truncate(300 << 20)
    for other in ("/dev/zero", "fifo", "big"):
        code, text = run(["bodydiff", "--git", "m.body", "m.body", "0" * 40, "100644", other, "1" * 40, "100644"], d)
        if code is None:
            continue
        expect(f"bodydiff --git with {other}: exit {code}, expected 2", code == 2, text)
        expect(f"bodydiff --git with {other}: no message", "io-read" in text or "error" in text, text)


def names_round_trip(root):
    """Item 16: every name comes back byte for byte."""
    d = os.path.join(root, "names")
    os.makedirs(d)
    case = os.path.join(SOURCE, "tests", "data", "hostile", "urdf_names_controls.urdf")
    code, text = run(["urdf2body", case, "-o", "out.body"], d)
    expect(f"urdf2body {case}: exit {code}", code == 0, text)
    if code != 0:
        return
    code, text = run(["bodyinfo", "--format", "yaml", "out.body"], d)
    expect(f"bodyinfo on what urdf2body wrote: exit {code}", code == 0, text)
    if code != 0:
        return
    names = set(re.findall(r"name: (.*)", text))
    loaded = set()
    for n in names:
        try:
            loaded.add(yaml.safe_load("v: " + n)["v"])
        except yaml.YAMLError:
            loaded.add(n)
    for name in ("a\x80b", "c \u2028 d", "e\ufffe\uffff" + "f", "g\x85h"):
        expect(f"the name {name!r} did not come back: {sorted(map(repr, loaded))}", name in loaded)


def main():
    with tempfile.TemporaryDirectory() as root:
        for check in (copy_meshes, unknown_scheme_kept, output_onto_mesh, standard_input, header_comment, bounded_reads, names_round_trip):
            sub = os.path.join(root, check.__name__)
            os.makedirs(sub)
            check(sub)
    for f in failures:
        print(f)
    print(f"urdf2body_files: {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
