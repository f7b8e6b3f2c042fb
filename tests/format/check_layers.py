#!/usr/bin/env python3
"""No folder includes one above it (docs/architecture.md): in libbodyfmt/src and in converters/,
each folder has a layer, and a file may include only its own folder or a lower layer.

A public header is placed with the code that implements it: <bodyfmt/X.h> with the folder of
libbodyfmt/src/*/X.cpp (or X_*.cpp; a header with no source is ground), and
<bodyfmt/converters/X.h> with the converters folder that holds it. Every folder found under the
two roots must have a layer below, so a new folder is placed on purpose and never skipped.

usage: check_layers.py [SOURCE_DIR]   (exit 1 and one line per include that runs upward)"""
import os
import re
import sys

# Ground first. A folder may include the folders before it in its list, never after.
LAYERS = {
    "libbodyfmt/src": ["text", "io", "diagnostic", "keys", "mesh", "model", "tessellate", "yaml",
                       "mesh_import", "load", "derived", "kinematics", "write", "fields", "diff", "fix"],
    "converters": ["core", "export", "urdf", "mjcf", "gltf"],
}
SOURCE_ENDINGS = (".cpp", ".h")
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)


def folders_of(root, base):
    found = {}
    for name in sorted(os.listdir(os.path.join(root, base))):
        path = os.path.join(root, base, name)
        if os.path.isdir(path):
            found[name] = path
    return found


def public_header_homes(root):
    """bodyfmt/X.h -> the libbodyfmt/src folder that implements it; bodyfmt/converters/X.h ->
    its converters folder. Also the headers that more than one folder implements, which have no
    single home and would otherwise go unchecked."""
    homes, several = {}, []
    src = os.path.join(root, "libbodyfmt/src")
    sources = [(os.path.relpath(folder, src).split(os.sep)[0], f)
               for folder, _, files in os.walk(src) for f in files if f.endswith(".cpp")]
    for header in sorted(os.listdir(os.path.join(root, "libbodyfmt/include/bodyfmt"))):
        stem = header[:-2]
        exact = {owner for owner, f in sources if f == stem + ".cpp"}
        prefixed = {owner for owner, f in sources if f.startswith(stem + "_")}
        # X.cpp names the home; X_*.cpp only where there is no X.cpp (model.h is model/model.cpp's,
        # not fields/model_fields.cpp's)
        owners = exact or prefixed
        if len(owners) == 1:
            homes["bodyfmt/" + header] = ("libbodyfmt/src", owners.pop())
        elif len(owners) > 1:
            several.append(f"libbodyfmt/include/bodyfmt/{header}: implemented in {', '.join(sorted(owners))}; "
                           "give it one home (rename the others)")
    for folder, path in folders_of(root, "converters").items():
        include = os.path.join(path, "include/bodyfmt/converters")
        if os.path.isdir(include):
            for header in os.listdir(include):
                homes["bodyfmt/converters/" + header] = ("converters", folder)
    return homes, several


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    homes, problems = public_header_homes(root)
    checked = 0
    for base, order in LAYERS.items():
        level = {name: i for i, name in enumerate(order)}
        folders = folders_of(root, base)
        for name in folders:
            if name not in level:
                problems.append(f"{base}/{name}: a folder with no layer (place it in tests/format/check_layers.py "
                                "and docs/architecture.md)")
        for name, path in folders.items():
            if name not in level:
                continue
            for folder, _, files in os.walk(path):
                for f in sorted(files):
                    if not f.endswith(SOURCE_ENDINGS):
                        continue
                    file = os.path.join(folder, f)
                    checked += 1
                    with open(file, encoding="utf-8", errors="replace") as text:
                        includes = INCLUDE.findall(text.read())
                    for included in includes:
                        target = None
                        if included in homes and homes[included][0] == base:
                            target = homes[included][1]
                        elif base == "libbodyfmt/src" and "/" in included and included.split("/")[0] in folders:
                            target = included.split("/")[0]
                        if target is None or target == name or target not in level:
                            continue
                        if level[target] > level[name]:
                            problems.append(f"{os.path.relpath(file, root)}: includes {included} "
                                            f"({base}/{target}), a layer above {base}/{name}")
    for p in problems:
        print(p)
    if checked < 100:
        print(f"only {checked} files found under {', '.join(LAYERS)}: is SOURCE_DIR the project's root?")
        return 1
    print(f"{checked} files checked, {len(problems)} includes against the layers")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
