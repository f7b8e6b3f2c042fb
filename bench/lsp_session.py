"""An LSP client for bench/run: drives bodyls as an editor does (initialize, didOpen, didChange)
and times each edit from didChange written to its publishDiagnostics read.

The server's memory comes from /proc/PID/status: VmRSS (now) and VmHWM (the peak so far).
"""
import json
import os
import re
import select
import subprocess
import time


class SessionError(Exception):
    pass


def uri_of(path):
    return "file://" + os.path.abspath(path)


def utf16_position(text, offset):
    """LSP position (line, UTF-16 code units) of the character offset `offset` of `text`."""
    line = text.count("\n", 0, offset)
    start = text.rfind("\n", 0, offset) + 1
    return {"line": line, "character": len(text[start:offset].encode("utf-16-le")) // 2}


def value_edits(text):
    """Two replacements of the first mass of `text` (else of the first translation's x, as in an
    assembly of SubBody links): to another value and back, so that a session alternates between
    two texts of the same size."""
    m = (re.search(r"\bmass:\s*([0-9.eE+-]+)", text)
         or re.search(r"\btranslation:\s*\[\s*([0-9.eE+-]+)", text))
    if not m:
        raise SessionError("no mass or translation to edit")
    old = m.group(1)
    new = "7.25" if old != "7.25" else "8.5"
    start = m.start(1)
    edited = text[:start] + new + text[m.end(1):]
    there = {"start": utf16_position(text, start), "end": utf16_position(text, start + len(old))}
    back = {"start": utf16_position(edited, start), "end": utf16_position(edited, start + len(new))}
    return [(there, new), (back, old)]


class Session:
    def __init__(self, server, timeout=60.0, init_options=None):
        self.proc = subprocess.Popen([server], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL, bufsize=0)
        self.buffer = b""
        self.timeout = timeout
        self.next_id = 0
        self.versions = {}
        params = {"processId": os.getpid(), "rootUri": None, "capabilities": {}}
        if init_options is not None:
            params["initializationOptions"] = init_options
        self.request("initialize", params)
        self.notify("initialized", {})

    def send(self, message):
        body = json.dumps(message).encode()
        self.proc.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)

    def notify(self, method, params):
        self.send({"jsonrpc": "2.0", "method": method, "params": params})

    def request(self, method, params):
        self.next_id += 1
        self.send({"jsonrpc": "2.0", "id": self.next_id, "method": method, "params": params})
        while True:
            message = self.read()
            if message.get("id") == self.next_id and "method" not in message:
                if "error" in message:
                    raise SessionError(f"{method}: {message['error']}")
                return message.get("result")

    def read(self):
        deadline = time.perf_counter() + self.timeout
        while True:
            head, sep, rest = self.buffer.partition(b"\r\n\r\n")
            if sep:
                m = re.search(rb"Content-Length:\s*(\d+)", head, re.I)
                if not m:
                    raise SessionError("a message without Content-Length")
                size = int(m.group(1))
                if len(rest) >= size:
                    self.buffer = rest[size:]
                    return json.loads(rest[:size])
            left = deadline - time.perf_counter()
            if left <= 0 or not select.select([self.proc.stdout], [], [], left)[0]:
                raise SessionError(f"no answer from the server within {self.timeout} s")
            chunk = os.read(self.proc.stdout.fileno(), 1 << 20)
            if not chunk:
                raise SessionError(f"the server exited ({self.proc.wait()})")
            self.buffer += chunk

    def wait_for_diagnostics(self, uri, version):
        """Reads until the document's diagnostics for `version` (any, for a server that names
        no version); answers the server's own requests with null."""
        while True:
            message = self.read()
            if "id" in message and "method" in message:
                self.send({"jsonrpc": "2.0", "id": message["id"], "result": None})
                continue
            if message.get("method") != "textDocument/publishDiagnostics":
                continue
            params = message["params"]
            if params.get("uri") == uri and params.get("version", version) == version:
                return params["diagnostics"]

    def open(self, path, text):
        """Seconds from didOpen to the document's first diagnostics."""
        uri = uri_of(path)
        self.versions[uri] = 1
        start = time.perf_counter()
        self.notify("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "body", "version": 1,
                                                              "text": text}})
        self.wait_for_diagnostics(uri, 1)
        return time.perf_counter() - start

    def change(self, path, edit_range, new_text):
        """Seconds from didChange (one incremental change) to its diagnostics."""
        uri = uri_of(path)
        self.versions[uri] += 1
        version = self.versions[uri]
        start = time.perf_counter()
        self.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": version},
                                               "contentChanges": [{"range": edit_range, "text": new_text}]})
        self.wait_for_diagnostics(uri, version)
        return time.perf_counter() - start

    def memory_kb(self):
        """(VmRSS, VmHWM) of the server in KB."""
        with open(f"/proc/{self.proc.pid}/status") as f:
            status = f.read()
        return tuple(int(re.search(rf"^{k}:\s*(\d+)", status, re.M).group(1)) for k in ("VmRSS", "VmHWM"))

    def close(self):
        try:
            self.request("shutdown", None)
            self.notify("exit", None)
            self.proc.wait(timeout=10)
        except (SessionError, OSError, subprocess.TimeoutExpired):
            self.proc.kill()
            self.proc.wait()
