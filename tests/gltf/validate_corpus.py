#!/usr/bin/env python3
"""The Khronos glTF validator on body2gltf's export of every corpus model Choreonoid loads.

usage: validate_corpus.py BODY2GLTF CORPUS_DIR NPM_PREFIX [EXTRA_MODELS...]

Each model is exported as GLB; the EXTRA_MODELS also with --both and as .gltf (JSON + .bin +
textures); every file must have 0 validator errors. Prints the remaining warning and info codes
with their counts, so that a new kind shows up in the test log (SUPPORT.md explains each one).
The validator is npm gltf-validator, installed into NPM_PREFIX by README command 2; without it
this test fails.
"""
import collections, os, pathlib, re, subprocess, sys, tempfile

def main():
    tool, corpus, npm = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    extra = [pathlib.Path(p) for p in sys.argv[4:]]
    modules = npm / "node_modules"
    if not (modules / "gltf-validator").is_dir():
        print(f"gltf-validator is not installed in {npm} (README command 2 installs it)")
        return 1
    models = []
    for ref in sorted((corpus / "reference").rglob("*.ref.yaml")):
        if re.search(r"^loaded: true$", ref.read_text(), re.M):
            rel = ref.relative_to(corpus / "reference").as_posix().replace(".ref.yaml", ".body")
            models.append(corpus / "choreonoid" / rel)
    models += extra
    if not models:
        print("no models found")
        return 1
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        outputs = []
        for i, model in enumerate(models):
            # Every model as GLB; the project's own examples also with --both and as .gltf.
            variants = [("glb", "model.glb", [])]
            if model in extra:
                variants += [("both", "model.glb", ["--both"]), ("gltf", "model.gltf", [])]
            for variant, name, args in variants:
                out = pathlib.Path(tmp) / f"{i}_{variant}" / name
                out.parent.mkdir()
                p = subprocess.run([tool, str(model), "-o", str(out), "-q", *args], capture_output=True, text=True)
                if p.returncode not in (0, 1) or not out.exists():
                    print(f"{model}: {variant}: body2gltf rc={p.returncode}: {p.stderr.strip()[-300:]}")
                    failures += 1
                    continue
                outputs.append((model, variant, out))
        p = subprocess.run(["node", str(pathlib.Path(__file__).with_name("validate_gltf.js")),
                            *[str(o) for _, _, o in outputs]],
                           capture_output=True, text=True, env={**os.environ, "NODE_PATH": str(modules)})
        lines = {l.split(" ", 1)[0]: l for l in p.stdout.splitlines()}
        codes = collections.Counter()
        for model, variant, out in outputs:
            line = lines.get(str(out))
            if line is None:
                print(f"{model}: {variant}: no validator result: {p.stderr.strip()[-300:]}")
                failures += 1
                continue
            m = re.search(r"errors=(\d+)", line)
            if not m or int(m.group(1)) != 0:
                print(f"{model}: {variant}: {line.split(' ', 1)[1]}")
                failures += 1
            cm = re.search(r"codes=(\S*)", line)
            for item in (cm.group(1).split(",") if cm and cm.group(1) else []):
                code, n = item.split(":")
                codes[code] += int(n)
    print(f"validated {len(outputs)} files from {len(models)} models; issues other than errors: "
          + (", ".join(f"{c} x{n}" for c, n in sorted(codes.items())) or "none"))
    print(f"gltf-validator: {len(outputs) - failures if failures <= len(outputs) else 0}/{len(outputs)} files with 0 errors")
    return 1 if failures else 0

if __name__ == "__main__":
    sys.exit(main())
