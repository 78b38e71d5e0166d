"""The service under attack (docs/security.md): a real ``serve`` process on a free
loopback port, sent what a flood would send. Printed: how fast and how small the answer to a
50 MB body is, the server's peak resident memory through four such bodies at once, and the
robot's situation round trip alone (before and after) and while Prolog queries that run to their
time limit keep coming, and what one commit costs at SQLite's synchronous=NORMAL and FULL.
tests/security uses the same client functions to assert the behaviour.
"""

from __future__ import annotations

from typing import Any

import json
import select
import socket
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request
from dataclasses import dataclass
from pathlib import Path

#: A body this large is what a flood sends (the limit is 1 MiB).
FLOOD_BYTES = 50 * 1024 * 1024
#: A query that runs until the service's time limit stops it.
ENDLESS_QUERY = "between(1, inf, X), X < 0"


@dataclass(frozen=True)
class Service:
    process: subprocess.Popen[bytes]
    port: int
    #: Where the service's stderr (its request log) goes: a file, never an unread pipe, which
    #: fills after some 1,000 requests and then blocks the service's event loop on its next line.
    log: Any = None

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"


@dataclass(frozen=True)
class Answer:
    status: int
    body: bytes
    seconds: float


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def start(store: Path, *extra: str, port: int | None = None, wait_s: float = 120) -> Service:
    """``oracle serve`` over ``store``, once it answers /api/health."""
    import tempfile

    port = port or free_port()
    log = tempfile.TemporaryFile()
    process = subprocess.Popen([sys.executable, "-m", "oracle", "serve", "--store", str(store), "--port", str(port), *extra],
                               stdout=subprocess.DEVNULL, stderr=log)
    deadline = time.monotonic() + wait_s
    while time.monotonic() < deadline:
        try:
            urllib.request.urlopen(f"http://127.0.0.1:{port}/api/health", timeout=2).read()
            return Service(process, port, log)
        except OSError:
            if process.poll() is not None:
                break
            time.sleep(0.1)
    process.kill()
    process.wait()
    log.seek(0)
    said = log.read().decode(errors="replace")
    log.close()
    raise RuntimeError(f"the service did not start: {said}")


def stop(service: Service) -> None:
    service.process.terminate()
    try:
        service.process.wait(timeout=20)
    except subprocess.TimeoutExpired:
        service.process.kill()
        service.process.wait()
    if service.log is not None:
        service.log.close()


def call(url: str, path: str, body: object = None, headers: dict[str, str] | None = None,
         timeout: float = 60) -> tuple[int, dict[str, Any], dict[str, str]]:
    """One request; its status, JSON answer and headers (lower-case names)."""
    data = None if body is None else json.dumps(body).encode()
    request = urllib.request.Request(url + path, data=data, headers={"Content-Type": "application/json", **(headers or {})})
    try:
        with urllib.request.urlopen(request, timeout=timeout) as response:
            raw, status, got = response.read(), response.status, response.headers
    except urllib.error.HTTPError as error:
        raw, status, got = error.read(), error.code, error.headers
    try:
        answer = json.loads(raw) if raw else {}
    except ValueError:
        answer = {"text": raw.decode("utf-8", "replace")}
    return status, answer, {k.lower(): v for k, v in got.items()}


def post_oversized(port: int, size: int = FLOOD_BYTES, chunked: bool = False, path: str = "/api/prolog") -> Answer:
    """POST ``size`` bytes of JSON-looking text, stopping as soon as the server answers; the
    answer's status and bytes, and the seconds from the first byte sent to the answer read."""
    started = time.perf_counter()
    with socket.create_connection(("127.0.0.1", port), timeout=30) as sock:
        length = b"Transfer-Encoding: chunked" if chunked else f"Content-Length: {size}".encode()
        sock.sendall(b"POST " + path.encode() + b" HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
                     + length + b"\r\n\r\n")
        piece = b"[" * 65536
        sent = 0
        try:
            while sent < size:
                readable, _, _ = select.select([sock], [], [], 0)
                if readable:
                    break  # the server has answered: stop sending
                chunk = piece if not chunked else b"%x\r\n" % len(piece) + piece + b"\r\n"
                sock.sendall(chunk)
                sent += len(piece)
            if chunked and sent >= size:
                sock.sendall(b"0\r\n\r\n")
        except (BrokenPipeError, ConnectionResetError):
            pass  # closed by the server after its answer
        data = b""
        try:
            while True:
                got = sock.recv(65536)
                if not got:
                    break
                data += got
                if b"\r\n\r\n" in data and _complete(data):
                    break
        except (ConnectionResetError, TimeoutError):
            pass
    seconds = time.perf_counter() - started
    head, _, body = data.partition(b"\r\n\r\n")
    status = int(head.split(b" ")[1]) if head.startswith(b"HTTP/") else 0
    return Answer(status, body, seconds)


def _complete(data: bytes) -> bool:
    head, _, body = data.partition(b"\r\n\r\n")
    for line in head.split(b"\r\n"):
        if line.lower().startswith(b"content-length:"):
            return len(body) >= int(line.split(b":")[1])
    return False


def peak_rss_mb(pid: int) -> float:
    """The process's peak resident memory so far (VmHWM), MB."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def flood(port: int, bodies: int = 4) -> list[Answer]:
    """``bodies`` oversized POSTs at once, half with a Content-Length, half chunked."""
    answers: list[Answer] = [Answer(0, b"", 0.0)] * bodies

    def one(i: int) -> None:
        answers[i] = post_oversized(port, chunked=bool(i % 2))

    threads = [threading.Thread(target=one, args=(i,)) for i in range(bodies)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return answers


def situation_latencies(url: str, neem: str, available: list[str], first_at: float, n: int) -> list[float]:
    """``n`` situations posted one after another, 1 s apart in NEEM time; round trips in ms."""
    times = []
    for i in range(n):
        started = time.perf_counter()
        status, _, _ = call(url, f"/api/neems/{neem}/situation", {"available": available, "at": first_at + i})
        times.append((time.perf_counter() - started) * 1000)
        if status != 200:
            raise RuntimeError(f"situation answered {status}")
    return sorted(times)


def commit_ms(folder: Path, synchronous: str, n: int) -> list[float]:
    """``n`` one-row commits to a WAL SQLite file at ``synchronous``; each one's ms, sorted."""
    import sqlite3

    conn = sqlite3.connect(folder / f"commits-{synchronous}.sqlite", isolation_level=None)
    conn.execute("PRAGMA journal_mode=WAL")
    conn.execute(f"PRAGMA synchronous={synchronous}")
    conn.execute("CREATE TABLE t (x BLOB)")
    times = []
    for _ in range(n):
        started = time.perf_counter()
        conn.execute("BEGIN")
        conn.execute("INSERT INTO t VALUES (randomblob(2000))")
        conn.execute("COMMIT")
        times.append((time.perf_counter() - started) * 1000)
    conn.close()
    return sorted(times)


def run(quick: bool = False) -> list[dict[str, Any]]:
    import tempfile

    from oracle.service.robot import percentile

    rows: list[dict[str, Any]] = []
    n = 30 if quick else 100
    with tempfile.TemporaryDirectory() as folder:
        for synchronous in ("NORMAL", "FULL"):
            values = commit_ms(Path(folder), synchronous, n * 2)
            p50, p99 = percentile(values, 50), percentile(values, 99)
            print(f"  one commit, WAL, synchronous={synchronous:6s} n={len(values)} p50 {p50:6.2f} ms  p99 {p99:6.2f} ms",
                  flush=True)
            rows.append({"area": "security", "name": f"commit synchronous={synchronous}", "p50_ms": round(p50, 3),
                         "p99_ms": round(p99, 3)})
        service = start(Path(folder) / "s.sqlite")
        try:
            available, at = robot_neem(service.url, "sec")
            rss_before = peak_rss_mb(service.process.pid)
            one = post_oversized(service.port)
            print(f"  50 MB body (Content-Length): {one.status} in {one.seconds * 1000:.1f} ms, answer {len(one.body)} bytes",
                  flush=True)
            chunked = post_oversized(service.port, chunked=True)
            print(f"  50 MB body (chunked):        {chunked.status} in {chunked.seconds * 1000:.1f} ms,"
                  f" answer {len(chunked.body)} bytes", flush=True)
            answers = flood(service.port, 4)
            rss_after = peak_rss_mb(service.process.pid)
            print(f"  4 x 50 MB at once: statuses {sorted(a.status for a in answers)}; peak RSS {rss_before:.0f} MB before,"
                  f" {rss_after:.0f} MB after", flush=True)
            rows += [{"area": "security", "name": "413 for 50 MB", "ms": round(one.seconds * 1000, 1), "bytes": len(one.body)},
                     {"area": "security", "name": "413 for 50 MB chunked", "ms": round(chunked.seconds * 1000, 1),
                      "bytes": len(chunked.body)},
                     {"area": "security", "name": "peak RSS, 4 floods", "mb": round(rss_after, 1)}]
            call(service.url, "/api/neems/sec/situation", {"available": available, "at": at})  # the session's fit
            alone = situation_latencies(service.url, "sec", available, at + 1, n)
            busy = threading.Event()

            def queries() -> None:
                while not busy.is_set():
                    call(service.url, "/api/prolog", {"query": ENDLESS_QUERY, "neem": "sec"})

            thread = threading.Thread(target=queries)
            thread.start()
            try:
                loaded = situation_latencies(service.url, "sec", available, at + 1 + n, n)
            finally:
                busy.set()
                thread.join()
            after = situation_latencies(service.url, "sec", available, at + 1 + 2 * n, n)  # drift, if any
            tasks = Path(f"/proc/{service.process.pid}/task")
            children = {c for task in tasks.iterdir() for c in (task / "children").read_text().split()}
            for child in sorted(children):
                print(f"  query process: peak RSS {peak_rss_mb(int(child)):.0f} MB", flush=True)
            for name, values in (("situation alone", alone), ("situation, queries running", loaded),
                                 ("situation alone, after", after)):
                p50, p99 = percentile(values, 50), percentile(values, 99)
                print(f"  {name:28s} n={len(values)} p50 {p50:7.1f} ms  p99 {p99:7.1f} ms", flush=True)
                rows.append({"area": "security", "name": name, "p50_ms": round(p50, 2), "p99_ms": round(p99, 2)})
            ratio = percentile(loaded, 99) / max(percentile(alone, 99), percentile(after, 99))
            print(f"  p99 with queries / p99 alone (the larger of before and after): {ratio:.2f} (target <= 2)", flush=True)
            rows.append({"area": "security", "name": "situation p99 ratio, queries running", "ratio": round(ratio, 2)})
        finally:
            stop(service)
    return rows


def robot_neem(url: str, neem: str) -> tuple[list[str], float]:
    """A NEEM ``neem`` of persona 0 with its first 20 actions logged through the service at
    ``url``: the tasks available after them and a moment 10 s after the last."""
    from oracle.service.robot import persona_rows

    user, steps = persona_rows(0, 3, 3)
    call(url, "/api/neems", {"user": user, "neem": neem})
    for row in steps[:20]:
        call(url, f"/api/neems/{neem}/actions", {"call": str(row.action), "begin": row.time.timestamp()})
    available = sorted({str(c) for row in steps[:20] for c in row.available} | {str(steps[0].action)})
    return available, steps[19].time.timestamp() + 10
