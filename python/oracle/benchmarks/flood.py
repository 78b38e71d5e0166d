"""The robot's situation posts while a flood runs (issue 54; docs/security.md, "Request limits").

A real ``serve`` process on a free loopback port. One robot posts situations one after another
(a new connection each, as ``security.call`` does): alone (the floor), then for ``FLOOD_SECONDS``
while another process keeps 100 idle sockets, 50 slow senders (a body byte a second) and a
stream of 1 MiB bodies (the worst shapes of ``worst_bodies`` and bodies one byte over the limit)
going, then alone again (drift). Printed: p50/p99 alone and under the flood, the 2x target, what
the flood's requests were answered. Then each worst body's event-loop time, measured in this
process on the real app: the loop thread's CPU time for the request and the longest stall a 1 ms
heartbeat saw (target: refused or answered within 50 ms of event-loop time).

Bounded: the flood stops by itself after its seconds (and is killed if it does not), loopback
only, every socket closed at the end.
"""

from __future__ import annotations

from typing import Any

import asyncio
import json
import os
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

#: How long the flood runs (seconds), and its parts.
FLOOD_SECONDS = 30
IDLE_SOCKETS = 100
SLOW_SENDERS = 50
BODY_STREAMS = 1
#: One MiB: the service's default body limit (the worst bodies are this long exactly).
MIB = 1 << 20


def worst_bodies(size: int = MIB) -> dict[str, bytes]:
    """Bodies of ``size`` bytes shaped to cost the most: escapes (the old regex's quadratic
    case), quotes, brackets, many values, many keys, long numbers, nesting just within the
    limit, one huge string, unicode escapes, and the most short strings the body check admits
    (which json.loads and pydantic then read on the event loop)."""

    def fill(head: bytes, unit: bytes, tail: bytes) -> bytes:
        """head, as many units as fit, tail; white space up to ``size``."""
        body = head + unit * ((size - len(head) - len(tail)) // max(len(unit), 1)) + tail
        return body + b" " * (size - len(body))

    keys = b",".join(b'"k%07d":0' % i for i in range((size - 2) // 13))
    return {
        "escaped quotes": fill(b'"', b'\\"', b'"'),
        "escaped backslashes": fill(b'"', b"\\\\", b'"'),
        "quote-heavy list": fill(b'["', b'","', b'"]'),
        "open brackets": b"[" * size,
        "alternating brackets": fill(b"", b"[{", b""),
        "many values": fill(b"[", b"1,", b"1]"),
        "many keys": fill(b"{" + keys, b"", b"}"),
        "long number": b"9" * size,
        "many 100-digit numbers": fill(b"[", b"9" * 100 + b",", b"1]"),
        "32 deep, then values": fill(b"[" * 31, b"[],", b"[]" + b"]" * 31),
        "one long string": fill(b'{"available": ["', b"a", b'"]}'),
        "unicode escapes": fill(b'{"available": ["', b"\\u00e9", b'"]}'),
        "47,000 short strings": fill(b'{"available": [' + b",".join([b'"' + b"x" * 19 + b'"'] * ((size - 20) // 22)),
                                                b"", b"]}"),
    }


def _situation(neem: str, body: bytes) -> bytes:
    return (b"POST /api/neems/" + neem.encode() + b"/situation HTTP/1.1\r\nHost: 127.0.0.1\r\n"
            b"Content-Type: application/json\r\nContent-Length: %d\r\n\r\n" % len(body)) + body


async def _flood(port: int, neem: str, seconds: float) -> dict[str, Any]:
    """The flood itself (one event loop: many sockets, one thread); what it was answered."""
    loop = asyncio.get_running_loop()
    stop_at = loop.time() + seconds
    counts: Counter[str] = Counter()
    bodies = [*worst_bodies().values(), b" " * (MIB + 1)]

    async def connect() -> tuple[asyncio.StreamReader, asyncio.StreamWriter] | None:
        try:
            return await asyncio.open_connection("127.0.0.1", port, limit=1 << 16)
        except OSError:
            counts["connect failed"] += 1
            await asyncio.sleep(0.05)
            return None

    async def idle() -> None:
        while loop.time() < stop_at:
            pair = await connect()
            if pair is None:
                continue
            counts["idle opened"] += 1
            try:
                got = await asyncio.wait_for(pair[0].read(4096), max(0.0, stop_at - loop.time()))
                counts["idle closed by the server" if not got or got.startswith(b"HTTP/1.1 503") else "idle answered"] += 1
            except (TimeoutError, OSError):
                pass
            pair[1].close()

    async def slow() -> None:
        while loop.time() < stop_at:
            pair = await connect()
            if pair is None:
                continue
            reader, writer = pair
            counts["slow opened"] += 1
            try:
                writer.write(_situation(neem, b"")[:-4].replace(b"Content-Length: 0", b"Content-Length: 1000") + b"\r\n\r\n")
                while loop.time() < stop_at:
                    writer.write(b" ")
                    await writer.drain()
                    try:
                        got = await asyncio.wait_for(reader.read(4096), 1.0)
                    except TimeoutError:
                        continue
                    counts[f"slow answered {got[9:12].decode(errors='replace')}" if got else "slow closed by the server"] += 1
                    break
            except OSError:
                counts["slow reset"] += 1
            writer.close()

    async def stream(offset: int) -> None:
        i = offset
        while loop.time() < stop_at:
            pair = await connect()
            if pair is None:
                continue
            reader, writer = pair
            body = bodies[i % len(bodies)]
            i += 1
            try:
                writer.write(_situation(neem, body))
                await writer.drain()
                got = await asyncio.wait_for(reader.read(4096), 30)
                counts[f"1 MiB body answered {got[9:12].decode(errors='replace')}" if got else "1 MiB body: no answer"] += 1
            except (OSError, TimeoutError):
                counts["1 MiB body: reset before its answer"] += 1
            writer.close()

    tasks = [*(idle() for _ in range(IDLE_SOCKETS)), *(slow() for _ in range(SLOW_SENDERS)),
             *(stream(k) for k in range(BODY_STREAMS))]
    await asyncio.gather(*tasks, return_exceptions=True)
    return {**counts, "cpu_s": round(time.process_time(), 2)}


def flood_main(port: int, neem: str, seconds: float) -> None:
    """Run the flood in this process and print what it was answered (JSON, one line)."""
    print(json.dumps(asyncio.run(_flood(port, neem, seconds))), flush=True)


def _robot(url: str, neem: str, available: list[str], first_at: float, until: float | None, n: int) -> list[float]:
    """Situations posted one after another (``n`` of them, or until ``until``); round trips in ms,
    each non-200 answer counted as a failure by raising."""
    from oracle.benchmarks.security import call

    times: list[float] = []
    i = 0
    while (until is None and i < n) or (until is not None and time.monotonic() < until):
        started = time.perf_counter()
        status, answer, _ = call(url, f"/api/neems/{neem}/situation", {"available": available, "at": first_at + i})
        times.append((time.perf_counter() - started) * 1000)
        if status != 200:
            raise RuntimeError(f"the robot's situation #{i} was answered {status}: {answer}")
        i += 1
        time.sleep(0.02)  # a robot posts when its world changes, not in a busy loop
    return sorted(times)


def _cpu_s(pid: int) -> float:
    """User + system CPU seconds of process ``pid`` so far."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def loop_times(bodies: dict[str, bytes], repeat: int = 5) -> dict[str, dict[str, Any]]:
    """Each body posted ``repeat`` times to the robot's situation route of the real app, in this
    process: its status, the event-loop thread's CPU ms for the request (the most of the runs)
    and the longest stall (ms) a heartbeat ticking every millisecond saw (the median of the runs,
    and the most)."""
    from oracle.algorithm.params import Hyperparameters
    from oracle.ontology import build_ontology
    from oracle.service import build_context
    from oracle.service.app import create_app

    with tempfile.TemporaryDirectory() as folder:
        ctx = build_context(str(Path(folder) / "s.sqlite"), build_ontology(), Hyperparameters())
        try:
            app = create_app(ctx)
            return asyncio.run(_loop_times(app, bodies, repeat))
        finally:
            ctx.thread.close()


async def _loop_times(app: Any, bodies: dict[str, bytes], repeat: int) -> dict[str, dict[str, Any]]:
    out: dict[str, dict[str, Any]] = {}
    await _post(app, "/api/neems", b'{"user": "ada", "neem": "ada"}')  # warm: routes, models, the session
    await _post(app, "/api/neems/ada/situation", b'{"available": ["pick(red_mug)"], "at": 1700000000}')
    for name, body in {"(none: the heartbeat alone, 50 ms)": b"", **bodies}.items():
        runs = [await _one(app, body) for _ in range(repeat)]
        stalls = sorted(stall for _, _, stall in runs)
        out[name] = {"status": runs[0][0], "loop_cpu_ms": max(cpu for _, cpu, _ in runs) * 1000,
                     "stall_ms": stalls[len(stalls) // 2] * 1000, "max_stall_ms": stalls[-1] * 1000}
    return out


async def _one(app: Any, body: bytes) -> tuple[int, float, float]:
    """One post of ``body`` (none: 50 ms of nothing): its status, the loop thread's CPU seconds
    and the longest stall (seconds) of a heartbeat ticking every millisecond."""
    stall = [0.0]
    done = asyncio.Event()

    async def heartbeat() -> None:
        last = time.perf_counter()
        while not done.is_set():
            await asyncio.sleep(0.001)
            now = time.perf_counter()
            stall[0] = max(stall[0], now - last - 0.001)
            last = now

    beat = asyncio.create_task(heartbeat())
    await asyncio.sleep(0.005)
    cpu = time.thread_time()
    status = 0
    if body:
        status = await _post(app, "/api/neems/ada/situation", body)
    else:
        await asyncio.sleep(0.05)
    cpu = time.thread_time() - cpu
    done.set()
    await beat
    return status, cpu, stall[0]


async def _post(app: Any, path: str, body: bytes) -> int:
    """One POST through the ASGI app (the body in 64 KiB pieces, as uvicorn hands it on)."""
    pieces = [body[i:i + (64 << 10)] for i in range(0, len(body), 64 << 10)] or [b""]
    queue = [{"type": "http.request", "body": piece, "more_body": k < len(pieces) - 1} for k, piece in enumerate(pieces)]
    status = [0]

    async def receive() -> dict[str, Any]:
        if queue:
            return queue.pop(0)
        await asyncio.sleep(3600)
        return {"type": "http.disconnect"}

    async def send(message: dict[str, Any]) -> None:
        if message["type"] == "http.response.start":
            status[0] = message["status"]

    scope = {"type": "http", "asgi": {"version": "3.0"}, "http_version": "1.1", "method": "POST", "scheme": "http",
             "path": path, "raw_path": path.encode(), "query_string": b"", "root_path": "",
             "headers": [(b"host", b"127.0.0.1"), (b"content-type", b"application/json"),
                         (b"content-length", str(len(body)).encode())],
             "client": ("127.0.0.1", 50000), "server": ("127.0.0.1", 8765)}
    await app(scope, receive, send)
    return status[0]


def run(quick: bool = False) -> list[dict[str, Any]]:
    from oracle.benchmarks.security import call, robot_neem, start, stop
    from oracle.service.robot import percentile

    rows: list[dict[str, Any]] = []
    seconds = 10 if quick else FLOOD_SECONDS
    n = 50 if quick else 150
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores while measuring", flush=True)
    with tempfile.TemporaryDirectory() as folder:
        service = start(Path(folder) / "s.sqlite")
        try:
            available, at = robot_neem(service.url, "robot")
            call(service.url, "/api/neems/robot/situation", {"available": available, "at": at})  # the session's fit
            alone = _robot(service.url, "robot", available, at + 1, None, n)
            cpu_before = _cpu_s(service.process.pid)
            flood = subprocess.Popen([sys.executable, "-c", "import sys; from oracle.benchmarks.flood import flood_main; "
                                      f"flood_main({service.port}, 'robot', {seconds})"],
                                     stdout=subprocess.PIPE, text=True)  # fmt: skip
            try:
                time.sleep(1.0)  # the flood's sockets open before the robot's first post
                loaded = _robot(service.url, "robot", available, at + 1 + n, time.monotonic() + seconds - 1.5, 0)
                answered = json.loads(flood.communicate(timeout=seconds + 60)[0].strip().splitlines()[-1])
                served_cpu = _cpu_s(service.process.pid) - cpu_before
            finally:
                if flood.poll() is None:
                    flood.kill()
                    flood.wait()
            after = _robot(service.url, "robot", available, at + 1 + n + len(loaded), None, n)
            for name, values in (("alone", alone), ("under the flood", loaded), ("alone, after", after)):
                p50, p99 = percentile(values, 50), percentile(values, 99)
                print(f"  situation {name:16s} n={len(values):4d} p50 {p50:7.1f} ms  p99 {p99:7.1f} ms  all 200", flush=True)
                rows.append({"area": "flood", "name": f"situation {name}", "n": len(values), "p50_ms": round(p50, 2),
                             "p99_ms": round(p99, 2)})
            floor = max(percentile(alone, 99), percentile(after, 99))
            ratio = percentile(loaded, 99) / floor
            print(f"  p99 under the flood / p99 alone (the larger of before and after): {ratio:.2f} (target <= 2)", flush=True)
            flood_cpu = answered.pop("cpu_s")
            print(f"  the flood ({IDLE_SOCKETS} idle, {SLOW_SENDERS} slow, {BODY_STREAMS} stream of 1 MiB bodies,"
                  f" {seconds} s) was answered: {json.dumps(answered, sort_keys=True)}", flush=True)
            print(f"  cpu seconds during the flood: the service {served_cpu:.1f} (robot's posts included), the flood's"
                  f" own process {flood_cpu:.1f}", flush=True)
            rows.append({"area": "flood", "name": "situation p99 ratio, flood", "ratio": round(ratio, 2), "flood": answered})
        finally:
            stop(service)
    measured = loop_times(worst_bodies(), 3 if quick else 5)
    for name, got in measured.items():
        print(f"  worst body {name:34s} {got['status']:3d}  loop cpu {got['loop_cpu_ms']:6.1f} ms"
              f"  longest stall {got['stall_ms']:6.1f} ms (median; most {got['max_stall_ms']:.1f})", flush=True)
        rows.append({"area": "flood", "name": f"worst body: {name}", **{k: round(v, 2) for k, v in got.items()}})
    worst = max(g["loop_cpu_ms"] for g in measured.values())
    stall = max(g["stall_ms"] for g in measured.values())
    print(f"  worst event-loop time of a 1 MiB body: {worst:.1f} ms of loop-thread cpu (target <= 50); longest stall"
          f" {stall:.1f} ms (a stall also holds waits for the GIL and for a core: compare the heartbeat alone)", flush=True)
    rows.append({"area": "flood", "name": "worst body event-loop ms", "ms": round(worst, 2), "stall_ms": round(stall, 2)})
    return rows

