"""A small LSP client for the protocol tests: starts bodyls, frames messages, reads replies
with a deadline (a test never hangs on a silent server)."""

import json
import os
import queue
import subprocess
import threading
import time

TIME_SCALE = float(os.environ.get("BODYFMT_TIME_SCALE", "1"))


class Client:
    def __init__(self, bodyls, args=(), cwd=None, env=None):
        self.proc = subprocess.Popen([bodyls, *args], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, cwd=cwd, env=env)
        self.messages = queue.Queue()
        self.next_id = 1
        self.backlog = []
        threading.Thread(target=self._read, daemon=True).start()
        threading.Thread(target=self._drain_stderr, daemon=True).start()
        self.stderr = b""

    def _drain_stderr(self):
        for line in self.proc.stderr:
            self.stderr += line

    def _read(self):
        out = self.proc.stdout
        while True:
            length = None
            while True:
                line = out.readline()
                if not line:
                    self.messages.put(None)
                    return
                line = line.strip()
                if not line:
                    break
                name, _, value = line.partition(b":")
                if name.strip().lower() == b"content-length":
                    length = int(value)
            body = out.read(length)
            self.messages.put(json.loads(body))

    def write_raw(self, data):
        self.proc.stdin.write(data)
        self.proc.stdin.flush()

    @staticmethod
    def frame(message):
        body = json.dumps(message).encode()
        return b"Content-Length: %d\r\n\r\n" % len(body) + body

    def send(self, message):
        self.write_raw(self.frame(message))

    def notify(self, method, params=None):
        self.send({"jsonrpc": "2.0", "method": method, "params": params or {}})

    def request_async(self, method, params=None):
        rid = self.next_id
        self.next_id += 1
        self.send({"jsonrpc": "2.0", "id": rid, "method": method, "params": params or {}})
        return rid

    def request(self, method, params=None, timeout=10):
        rid = self.request_async(method, params)
        return self.wait(lambda m: m.get("id") == rid and "method" not in m, timeout)

    def wait(self, predicate, timeout=10):
        """The first message (kept or new) matching predicate; the others stay in the backlog."""
        for i, m in enumerate(self.backlog):
            if predicate(m):
                return self.backlog.pop(i)
        deadline = time.time() + timeout * TIME_SCALE
        while True:
            left = deadline - time.time()
            if left <= 0:
                raise AssertionError("no matching message within %.1f s; backlog: %s" % (timeout, self.backlog[-5:]))
            try:
                m = self.messages.get(timeout=left)
            except queue.Empty:
                continue
            if m is None:
                raise AssertionError("bodyls closed its output; stderr: %s" % self.stderr.decode(errors="replace"))
            if predicate(m):
                return m
            self.backlog.append(m)

    def diagnostics(self, uri, version=None, timeout=20):
        def match(m):
            return (m.get("method") == "textDocument/publishDiagnostics" and m["params"]["uri"] == uri and
                    (version is None or m["params"].get("version") == version))
        return self.wait(match, timeout)["params"]["diagnostics"]

    def initialize(self, capabilities=None, options=None):
        params = {"processId": os.getpid(), "rootUri": None, "capabilities": capabilities or {}}
        if options is not None:
            params["initializationOptions"] = options
        reply = self.request("initialize", params)
        self.notify("initialized", {})
        return reply

    def open(self, uri, text, version=1):
        self.notify("textDocument/didOpen",
                    {"textDocument": {"uri": uri, "languageId": "body", "version": version, "text": text}})

    def change(self, uri, version, changes):
        self.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": version},
                                               "contentChanges": changes})

    def finish(self, timeout=10):
        """shutdown, exit; returns the exit code."""
        self.request("shutdown")
        self.notify("exit")
        return self.proc.wait(timeout=timeout * TIME_SCALE)

    def kill(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()


def uri_of(path):
    from urllib.parse import quote
    return "file://" + quote(os.path.abspath(path))


def utf16_column(line_text, byte_column):
    """0-based UTF-16 column of a 1-based byte column in a line (bytes), independently of bodyls."""
    prefix = line_text[:max(byte_column - 1, 0)].decode("utf-8", errors="replace")
    return sum(2 if ord(c) > 0xFFFF else 1 for c in prefix)
