"""Where one robot's situation spends its time in the service, without HTTP: the job's parts as
the route runs them alone (routes.situation: the imagining written and committed, then ranked),
the flush the answer waits for (on the syncer's thread, from the commit until the group's future
resolves, and what of it is left once the job ends), and the answer's JSON (Starlette's
JSONResponse, as the route answers it: time and size). The rest of a round trip is HTTP and the
hand-offs between threads: `python -m oracle bench --only service` prints the round trip, the
job's own time and the `GET /api/health` floor beside it (docs/service.md).

Usage: python experiments/situation-parts.py [STEPS] [FOLDER]
One NEEM of 1,000 logged actions (the bench's persona 0, `benchmarks.service._prepare`; made once
in FOLDER, default /tmp/neem-situation-parts, and copied per run), booted as `serve` does; then
STEPS (default 60) situations, each followed by its action and the warm-up after it, as the
service runs them; the first 5 are not counted. Printed: p50, p99 and mean ms of each part.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

from starlette.responses import JSONResponse

from oracle.benchmarks.service import _prepare, booted_copy, robot_rows
from oracle.service.robot import percentile
from oracle.service.routes import routine_now, stored_reader

WARM = 5


def main(steps: int, folder: Path) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    store = folder / "one.sqlite"
    if not store.exists():
        _prepare(store, 1, 1000, steps)
    _, rows = robot_rows(0, 1000 + steps)
    todo = rows[1000:1000 + steps]
    ctx = booted_copy(store, folder / "work.sqlite")
    ctx.thread.call(ctx.engine.session, "bench-0")
    times: dict[str, list[float]] = {}

    def situation(row: object) -> tuple[object, float, list[float]]:
        group = ctx.thread.group
        assert group is not None
        marks = [time.perf_counter()]
        done = group.join()
        session = ctx.engine.session("bench-0")
        available = [str(c) for c in row.available or (row.action,)]  # type: ignore[attr-defined]
        found = session.offer(available, row.time.isoformat())  # type: ignore[attr-defined]
        session.write_imagined(found)
        marks.append(time.perf_counter())
        group.commit()
        marks.append(time.perf_counter())
        resolved: list[float] = []
        done.add_done_callback(lambda _: resolved.append(time.perf_counter()))
        ranking, ms = session.rank(found)
        marks.append(time.perf_counter())
        answer = dict(session.describe(found, ranking, ms))
        marks.append(time.perf_counter())
        answer["routine"] = routine_now(ctx.engine, session, found.when.seconds)
        marks.append(time.perf_counter())
        for name, (a, b) in zip(("written", "committed", "ranked (chain included)", "described (words, modes)",
                                 "routine"), zip(marks, marks[1:])):
            times.setdefault(name, []).append((b - a) * 1000)
        times.setdefault("the job", []).append((marks[-1] - marks[0]) * 1000)
        return done, marks[2], resolved

    def action(row: object) -> None:
        group = ctx.thread.group
        assert group is not None
        done = group.join()
        session = ctx.engine.session("bench-0")
        end = row.end.isoformat() if row.end is not None else None  # type: ignore[attr-defined]
        session.log(str(row.action), row.time.isoformat(), end)  # type: ignore[attr-defined]
        group.commit()
        done.result()
        session.warm.warm(session.ranker, session.ranker.last_end, stored_reader(ctx.engine, session))

    try:
        for index, row in enumerate(todo):
            if index == WARM:
                times.clear()
            done, committed, resolved = ctx.thread.call(situation, row)
            ended = time.perf_counter()  # the job's answer handed back (after any flush left)
            done.result()  # type: ignore[attr-defined]
            flushed = resolved[0] if resolved else time.perf_counter()
            times.setdefault("flush, from the commit", []).append((flushed - committed) * 1000)
            times.setdefault("flush left after the job", []).append(max(0.0, flushed - ended) * 1000)
            latest = ctx.thread.call(lambda: ctx.engine.session("bench-0").latest)
            started = time.perf_counter()
            body = JSONResponse(latest).body
            times.setdefault("the answer's JSON", []).append((time.perf_counter() - started) * 1000)
            times.setdefault("the answer's bytes / 1000", []).append(len(body) / 1000)
            ctx.thread.call(action, row)
    finally:
        ctx.thread.close()
    print(f"1 robot, {len(todo) - WARM} situations at 1,000 actions; load average {os.getloadavg()[0]:.1f}", flush=True)
    for name, values in times.items():
        values.sort()
        print(f"  {name:28s} p50 {percentile(values, 50):7.2f}  p99 {percentile(values, 99):7.2f}"
              f"  mean {sum(values) / len(values):7.2f}", flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 60, Path(sys.argv[2]) if len(sys.argv) > 2 else Path("/tmp/neem-situation-parts"))
