#!/usr/bin/env python3
"""The set-ups in editors/ that CI cannot run in their editor (VS Code, Kate) still parse and
agree with the others: one language id, `body`, for `*.body` files, and the command `bodyls`.

usage: setup_files.py EDITORS_DIR NODE

- vscode/package.json is JSON declaring the language `body` for `.body`, activated on it, with
  `main` an existing file, the setting `bodyls.path` (default `bodyls`) and vscode-languageclient
  as a dependency; `node --check` accepts extension.js, which starts the client for `body`.
- kate/body.xml is well-formed, names the highlighting `Body` for `*.body` on YAML's rules, and
  kate/lspclient.json's `body` server runs `bodyls` for a highlighting mode its regex matches.
- nvim/lua/bodyls.lua and emacs/bodyls.el (run by lsp.editor.neovim and lsp.editor.eglot) use the
  same language id: the filetype `body`, and `body-mode`, which eglot sends as `body`.
"""
import json
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET


def main():
    editors, node = sys.argv[1], sys.argv[2]
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    def read(*parts):
        with open(os.path.join(editors, *parts), encoding="utf-8") as f:
            return f.read()

    try:
        package = json.loads(read("vscode", "package.json"))
        languages = package.get("contributes", {}).get("languages", [])
        check(any(l.get("id") == "body" and ".body" in l.get("extensions", []) for l in languages),
              "vscode/package.json: no language `body` for .body files")
        check("onLanguage:body" in package.get("activationEvents", []),
              "vscode/package.json: not activated on the language body")
        commands = package.get("contributes", {}).get("commands", [])
        check(any(c.get("command") == "bodyls.view" for c in commands),
              "vscode/package.json: the command bodyls.view is not contributed")
        check(os.path.isfile(os.path.join(editors, "vscode", package.get("main", ""))),
              f"vscode/package.json: main {package.get('main')!r} is no file")
        setting = package.get("contributes", {}).get("configuration", {}).get("properties", {}).get("bodyls.path", {})
        check(setting.get("default") == "bodyls", "vscode/package.json: no setting bodyls.path defaulting to bodyls")
        check("vscode-languageclient" in package.get("dependencies", {}),
              "vscode/package.json: vscode-languageclient is not a dependency")
        for name in ("language-configuration.json",):
            json.loads(read("vscode", name))
    except (ValueError, OSError) as e:
        failures.append(f"vscode: {e}")
    extension = os.path.join(editors, "vscode", "extension.js")
    if not os.access(node, os.X_OK):
        failures.append(f"node is not installed ({node}): README.md's install command installs it")
    else:
        run = subprocess.run([node, "--check", extension], capture_output=True, text=True)
        check(run.returncode == 0, f"node --check {extension}: {run.stderr[-400:]}")
    try:
        source = read("vscode", "extension.js")
        check('require("vscode-languageclient/node")' in source and 'language: "body"' in source,
              "vscode/extension.js: does not start vscode-languageclient for the language body")
        check('registerCommand("bodyls.view"' in source and '"bodyls.openViewer"' in source,
              "vscode/extension.js: no command bodyls.view asking bodyls.openViewer")
    except OSError as e:
        failures.append(str(e))

    try:
        language = ET.fromstring(read("kate", "body.xml").encode())
        check(language.get("name") == "Body" and "*.body" in (language.get("extensions") or "").split(";"),
              "kate/body.xml: not the highlighting Body for *.body")
        check(any(rule.get("context") == "##YAML" for rule in language.iter("IncludeRules")),
              "kate/body.xml: does not use YAML's rules")
        servers = json.loads(read("kate", "lspclient.json")).get("servers", {})
        body = servers.get("body", {})
        check(body.get("command", [None])[0] == "bodyls", "kate/lspclient.json: the body server is not bodyls")
        check(bool(re.search(body.get("highlightingModeRegex", "(?!)"), language.get("name") or "")),
              "kate/lspclient.json: the body server's highlightingModeRegex does not match the highlighting Body")
    except (ValueError, OSError, ET.ParseError) as e:
        failures.append(f"kate: {e}")

    try:
        check('filetype = "body"' in read("nvim", "lua", "bodyls.lua"), "nvim/lua/bodyls.lua: no filetype body")
        check("(define-derived-mode body-mode" in read("emacs", "bodyls.el"), "emacs/bodyls.el: no body-mode")
    except OSError as e:
        failures.append(str(e))

    for f in failures:
        print("FAIL: " + f)
    print("editor set-ups: " + ("FAIL" if failures else "OK"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
