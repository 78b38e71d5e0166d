"""What a hostile ``/api/prolog`` query costs the service (issue 54): a query that builds a 2 GiB
atom by doubling, one whose answer is 12 million characters, and one whose answer fills the
stack, each against a real ``serve`` process. Printed: each query's status, time and error, the
service's resident memory (VmRSS) before and after all of them (target: grows by < 50 MB) and
the query child's peak; the floor beside them is a plain ``X = 1`` query's time and the service's
RSS before any hostile query.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

from oracle.benchmarks.security import call, start, stop


def doubling(steps: int, answer: bool = False) -> str:
    """A query that doubles an atom ``steps`` times: 2**steps characters, no stack used."""
    parts = ["atom_concat(x, x, A1)"] + [f"atom_concat(A{i}, A{i}, A{i + 1})" for i in range(1, steps)]
    return ", ".join(parts) + (f", Big = A{steps}" if answer else f", atom_length(A{steps}, Length)")


#: (name, query): the hostile queries, run in this order.
HOSTILE = (("2 GiB atom", doubling(31)), ("12 M-character answer", doubling(22, answer=True)),
           ("answer past the stack", doubling(25, answer=True)))


def rss_mb(pid: int, field: str = "VmRSS") -> float:
    """The process's resident memory (``VmRSS``) or its peak (``VmHWM``), MB."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith(field + ":"):
            return int(line.split()[1]) / 1024
    return float("nan")


def children(pid: int) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                if int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1]) == pid:
                    found.append(int(entry.name))
            except (OSError, IndexError, ValueError):
                continue
    return found


def run(quick: bool = False) -> list[dict[str, Any]]:
    import tempfile

    rows: list[dict[str, Any]] = []
    with tempfile.TemporaryDirectory() as folder:
        service = start(Path(folder) / "s.sqlite")
        try:
            call(service.url, "/api/neems", {"user": "ada", "neem": "ada"})
            began = time.perf_counter()
            status, _, _ = call(service.url, "/api/prolog", {"query": "X = 1", "neem": "ada"})
            floor_ms = (time.perf_counter() - began) * 1000
            before = rss_mb(service.process.pid)
            print(f"  floor: X = 1 answered {status} in {floor_ms:.0f} ms (first query: starts the child);"
                  f" service RSS {before:.0f} MB", flush=True)
            rows.append({"area": "querylimits", "name": "floor X = 1", "ms": round(floor_ms, 1), "rss_mb": round(before, 1)})
            peak_child = 0.0
            for name, query in HOSTILE:
                began = time.perf_counter()
                status, answer, _ = call(service.url, "/api/prolog", {"query": query, "neem": "ada"})
                ms = (time.perf_counter() - began) * 1000
                for child in children(service.process.pid):
                    peak_child = max(peak_child, rss_mb(child, "VmHWM"))
                error = str(answer.get("error", answer) if isinstance(answer, dict) else answer)[:90]
                print(f"  {name:24s} {status} in {ms:6.0f} ms: {error}", flush=True)
                rows.append({"area": "querylimits", "name": name, "status": status, "ms": round(ms, 1)})
            status, _, _ = call(service.url, "/api/prolog", {"query": "X = 1", "neem": "ada"})
            after = rss_mb(service.process.pid)
            print(f"  service RSS {before:.0f} -> {after:.0f} MB (+{after - before:.1f}; target < 50);"
                  f" query child peak {peak_child:.0f} MB; X = 1 afterwards: {status}", flush=True)
            rows.append({"area": "querylimits", "name": "service RSS growth", "mb": round(after - before, 1),
                         "child_peak_mb": round(peak_child, 1)})
        finally:
            stop(service)
    return rows
