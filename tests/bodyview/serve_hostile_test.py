#!/usr/bin/env python3
"""bodyview --serve among hostile neighbours (issue 34).

usage: serve_hostile_test.py BODYVIEW WORK_DIR

Starts `bodyview --serve` on a small model of its own and checks, over loopback sockets:
- it listens on 127.0.0.1 only (/proc/net/tcp);
- only the Host names of the URL are answered (127.0.0.1:PORT, localhost:PORT, [::1]:PORT); any
  other Host (a DNS-rebinding page's), none, or two get 421 and no page;
- HEAD gets the headers of GET and no body; POST, PUT, DELETE, OPTIONS get 405 with Allow;
- while ten idle connections, a client that asked for the page and never reads, and a slowloris
  (a byte every 0.3 s) are connected, and after 100 more idle connections, a GET answers within
  a second and live reload still follows an edit;
- SIGTERM and SIGINT stop it (exit 0) within a second whatever those clients do.
"""
import os, pathlib, signal, socket, subprocess, sys, threading, time

MODEL = """format: ChoreonoidBody
format_version: 2.0
name: Hostile
links:
  - name: BASE
    joint_type: free
    mass: {mass}
    inertia: [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01]
    elements:
      - type: Shape
        geometry: {{ type: Box, size: [0.3, 0.3, 0.3] }}
"""


def request(port, head, timeout=5.0):
    """Sends `head` and reads to the end: (status line, headers dict, body, seconds)."""
    start = time.monotonic()
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        s.sendall(head.encode())
        data = b""
        while chunk := s.recv(1 << 16):
            data += chunk
    top, _, body = data.partition(b"\r\n\r\n")
    lines = top.decode("latin-1").split("\r\n")
    headers = dict(line.split(": ", 1) for line in lines[1:] if ": " in line)
    return lines[0], headers, body, time.monotonic() - start


def answers(port, text, timeout=5.0):
    """Sends `text` (requests pipelined on one connection), reads to the end and splits what
    came back at each answer's Content-Length: [(status line, body)]."""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        s.sendall(text.encode())
        data = b""
        while chunk := s.recv(1 << 16):
            data += chunk
    out = []
    while data:
        top, _, rest = data.partition(b"\r\n\r\n")
        lines = top.decode("latin-1").split("\r\n")
        headers = dict(line.split(": ", 1) for line in lines[1:] if ": " in line)
        size = int(headers.get("Content-Length", len(rest)))
        out.append((lines[0], rest[:size]))
        data = rest[size:]
    return out


def get(port, target="/", host=None, method="GET", timeout=5.0):
    host_line = "" if host == "" else f"Host: {host or f'127.0.0.1:{port}'}\r\n"
    return request(port, f"{method} {target} HTTP/1.1\r\n{host_line}\r\n", timeout)


def listening_addresses(port):
    out = []
    for table in ("/proc/net/tcp", "/proc/net/tcp6"):
        if os.path.exists(table):
            for line in open(table).read().splitlines()[1:]:
                local, state = line.split()[1], line.split()[3]
                if state == "0A" and int(local.rsplit(":", 1)[1], 16) == port:
                    out.append(local.rsplit(":", 1)[0])
    return out


class Hostiles:
    """Ten idle connections, a client that asked for the page and never reads, a slowloris."""

    def __init__(self, port, extra_idle=0):
        self.sockets, self.stop = [], threading.Event()
        for _ in range(10 + extra_idle):
            self.sockets.append(socket.create_connection(("127.0.0.1", port)))
        stalled = socket.socket()
        stalled.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
        stalled.connect(("127.0.0.1", port))
        stalled.sendall(f"GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n".encode())
        self.sockets.append(stalled)
        self.slow = socket.create_connection(("127.0.0.1", port))
        self.thread = threading.Thread(target=self.slowloris, daemon=True)
        self.thread.start()

    def slowloris(self):
        text = b"GET / HTTP/1.1\r\nX-Padding: " + b"a" * 100000
        for byte in text:
            if self.stop.wait(0.3):
                return
            try:
                self.slow.send(bytes([byte]))
            except OSError:
                return

    def close(self):
        self.stop.set()
        for s in self.sockets + [self.slow]:
            s.close()


def start(tool, model):
    server = subprocess.Popen([tool, "--serve", "-q", str(model)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              text=True)
    url = server.stdout.readline().strip()
    if not url.startswith("http://127.0.0.1:"):
        raise AssertionError(f"bodyview --serve printed {url!r}")
    return server, int(url.rsplit(":", 1)[1].strip("/"))


def stop_time(server, sig):
    start_time = time.monotonic()
    server.send_signal(sig)
    try:
        rc = server.wait(timeout=10)
    except subprocess.TimeoutExpired:
        server.kill()
        server.wait()
        return "hung", 10.0
    return rc, time.monotonic() - start_time


def main():
    tool, work = sys.argv[1], pathlib.Path(sys.argv[2])
    work.mkdir(parents=True, exist_ok=True)
    model = work / "hostile.body"
    model.write_text(MODEL.format(mass=1.0))
    failures = []
    server, port = start(tool, model)
    hostiles = None
    try:
        addresses = listening_addresses(port)
        if addresses != ["0100007F"]:
            failures.append(f"listens on {addresses}, not 127.0.0.1 only (0100007F)")
        status, headers, page, _ = get(port)
        if not status.endswith("200 OK") or b"bv-data" not in page:
            failures.append(f"GET / with Host 127.0.0.1:{port}: {status}")
        for host in (f"localhost:{port}", f"[::1]:{port}", f"LOCALHOST:{port}"):
            status, _, body, _ = get(port, host=host)
            if not status.endswith("200 OK") or body != page:
                failures.append(f"Host {host}: {status}")
        for host in (f"evil.example:{port}", "127.0.0.1", f"127.0.0.1:{port + 1}", f"127.0.0.1.evil.example:{port}", ""):
            for target in ("/", "/status"):
                status, _, body, _ = get(port, target, host=host)
                if " 421 " not in status or b"bv-data" in body or b"generation" in body:
                    failures.append(f"Host {host!r} {target}: {status}, {len(body)} bytes")
        status, _, body, _ = request(port, f"GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nHost: evil.example\r\n\r\n")
        if " 421 " not in status:
            failures.append(f"two Host headers: {status}")
        # Requests pipelined on one connection are parsed one at a time (issue 45): each is
        # answered, each by its own Host header.
        ok, evil = f"Host: 127.0.0.1:{port}\r\n", "Host: evil.example\r\n"
        for requests, expected in (
            ([f"GET / HTTP/1.1\r\n{ok}\r\n", f"GET /status HTTP/1.1\r\n{ok}\r\n"], ["200", "200"]),
            ([f"GET / HTTP/1.1\r\n{ok}\r\n"] * 3, ["200", "200", "200"]),
            ([f"GET / HTTP/1.1\r\n{ok}\r\n", f"GET / HTTP/1.1\r\n{evil}\r\n"], ["200", "421"]),
            ([f"GET / HTTP/1.1\r\n{evil}\r\n", f"GET / HTTP/1.1\r\n{ok}\r\n"], ["421"]),
            ([f"GET / HTTP/1.1\r\n{ok}\r\n", f"GET / HTTP/1.1\r\n{ok}{evil}\r\n"], ["200", "421"]),
            # A request's body is no request: nothing after a POST is answered.
            ([f"POST / HTTP/1.1\r\n{ok}Content-Length: 30\r\n\r\n", f"GET / HTTP/1.1\r\n{ok}\r\n"], ["405"]),
            ([f"GET / HTTP/1.1\r\n{ok}Connection: close\r\n\r\n", f"GET / HTTP/1.1\r\n{ok}\r\n"], ["200"]),
        ):
            got = answers(port, "".join(requests))
            statuses = [line.split(" ")[1] if " " in line else line for line, _ in got]
            if statuses != expected:
                failures.append(f"pipelined {len(requests)} requests: answered {statuses}, expected {expected}")
            for (line, body), status in zip(got, statuses):
                if status == "200" and b"bv-data" not in body and b"generation" not in body:
                    failures.append(f"pipelined: a 200 answer without the page or the status ({len(body)} bytes)")
        print(f"pipelined requests: {len(got)} answers on the last connection")
        status, headers, body, _ = get(port, method="HEAD")
        if not status.endswith("200 OK") or body or headers.get("Content-Length") != str(len(page)):
            failures.append(f"HEAD: {status}, {headers.get('Content-Length')} (page {len(page)}), body {len(body)}")
        for method in ("POST", "PUT", "DELETE", "OPTIONS", "PATCH"):
            status, headers, body, _ = get(port, method=method)
            if " 405 " not in status or headers.get("Allow") != "GET, HEAD" or b"bv-data" in body:
                failures.append(f"{method}: {status}, Allow {headers.get('Allow')}")

        hostiles = Hostiles(port)
        time.sleep(0.5)
        status, _, body, seconds = get(port)
        print(f"GET with 10 idle connections, a stalled reader and a slowloris: {seconds * 1000:.0f} ms")
        if body != page or seconds > 1.0:
            failures.append(f"GET among hostile clients: {status}, {seconds:.2f} s")
        generation = int(get(port, "/status")[2].split(b'"generation":')[1].split(b",")[0])
        time.sleep(0.05)
        model.write_text(MODEL.format(mass=2.0))
        deadline, reloaded = time.monotonic() + 5, False
        while time.monotonic() < deadline and not reloaded:
            reloaded = int(get(port, "/status")[2].split(b'"generation":')[1].split(b",")[0]) > generation
            time.sleep(0.1)
        if not reloaded:
            failures.append("live reload did not follow an edit among hostile clients")
        more = [socket.create_connection(("127.0.0.1", port)) for _ in range(100)]
        status, _, body, seconds = get(port)
        print(f"GET after 100 more idle connections: {seconds * 1000:.0f} ms")
        if not status.endswith("200 OK") or seconds > 2.0:
            failures.append(f"GET after 100 more idle connections: {status}, {seconds:.2f} s")
        rc, seconds = stop_time(server, signal.SIGTERM)
        print(f"SIGTERM among hostile clients: exit {rc} in {seconds * 1000:.0f} ms")
        if rc != 0 or seconds > 1.0:
            failures.append(f"SIGTERM among hostile clients: exit {rc} after {seconds:.2f} s")
        for s in more:
            s.close()
        hostiles.close()

        server, port = start(tool, model)
        hostiles = Hostiles(port)
        time.sleep(0.5)
        rc, seconds = stop_time(server, signal.SIGINT)
        print(f"SIGINT among hostile clients: exit {rc} in {seconds * 1000:.0f} ms")
        if rc != 0 or seconds > 1.0:
            failures.append(f"SIGINT among hostile clients: exit {rc} after {seconds:.2f} s")
        # --lifeline names a descriptor to read: one not open, or open for writing only, is
        # refused with a located error (exit 2), never taken for a lifeline that has ended.
        with open(work / "written", "w") as written:
            for fd, keep in ((written.fileno(), (written.fileno(),)), (987, ())):
                refused = subprocess.run([tool, "--serve", "-q", str(model), "--lifeline", str(fd)], pass_fds=keep,
                                         capture_output=True, text=True, timeout=30)
                if refused.returncode != 2 or "--lifeline %d" % fd not in refused.stderr:
                    failures.append(f"--lifeline {fd} (not readable): exit {refused.returncode}, {refused.stderr!r}")
        # A readable lifeline: bodyview serves until its writer closes it, then exits 0 at once.
        read_end, write_end = os.pipe()
        lived = subprocess.Popen([tool, "--serve", "-q", str(model), "--lifeline", str(read_end)], pass_fds=(read_end,),
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        os.close(read_end)
        if not lived.stdout.readline().startswith("http://127.0.0.1:"):
            failures.append("--lifeline: no page served")
        os.close(write_end)
        try:
            if lived.wait(timeout=10) != 0:
                failures.append(f"--lifeline: exit {lived.returncode} when its writer closed it")
        except subprocess.TimeoutExpired:
            lived.kill()
            lived.wait()
            failures.append("--lifeline: still serving 10 s after its writer closed it")
    except (AssertionError, OSError, IndexError, ValueError, subprocess.TimeoutExpired) as e:
        failures.append(f"{type(e).__name__}: {e}")
    finally:
        if hostiles:
            hostiles.close()
        if server.poll() is None:
            server.kill()
            server.wait()
    for f in failures:
        print("FAIL: " + f)
    print("serve_hostile: " + ("FAIL" if failures else "OK"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
