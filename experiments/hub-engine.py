"""The engine thread's own work per robot-step with many robots on one process, without HTTP:
where one process stops scaling (docs/service.md, "Many robots on one hub").

Usage: python experiments/hub-engine.py ROBOTS [FOLDER]
Prepares (once, kept in FOLDER, default /tmp/neem-hub-engine) ROBOTS NEEMs of 1,000 logged actions
each, as `bench --only service` does (`benchmarks.service._prepare`), copies the store, builds the
service's context and boots it as `serve` does, opens every NEEM's session, then posts 20 steps per
robot interleaved (robot 1's step, robot 2's, ...): per step the situation's job as it runs alone
(the imagined situation written, its commit, then the ranking, chain and routine), the ranking
written back in a lingering group, the action's job, its commit and the warm-up after it, each
timed on the engine thread, and apart each commit's flush on the syncer's thread (from the commit
to its group's future resolving: what an answer waits for beyond the engine); the first two
rounds are not counted. Printed: p50, p99 and mean ms of each part, and of their sum per
robot-step; one engine thread serves at most 1,000 / mean-sum robot-steps a second.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

from oracle.benchmarks.service import _prepare, booted_copy, robot_rows
from oracle.service.robot import percentile
from oracle.service.routes import routine_now, stored_reader

STEPS, WARM_ROUNDS = 20, 2


def main(robots: int, folder: Path) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    store = folder / f"hub{robots}.sqlite"
    if not store.exists():
        started = time.perf_counter()
        _prepare(store, robots, 1000, STEPS)
        print(f"prepared {robots} NEEMs in {time.perf_counter() - started:.0f} s", flush=True)
    # the steps to post made again (the personas' rows are the same each call): nothing is read
    # back from the folder but the store
    plans = []
    for robot in range(robots):
        user, rows = robot_rows(robot, 1000 + STEPS)
        plans.append((f"bench-{robot}", user, rows[1000:1000 + STEPS]))
    ctx = booted_copy(store, folder / "work.sqlite")
    started = time.perf_counter()
    for neem, _, _ in plans:
        ctx.thread.call(ctx.engine.session, neem)
    print(f"session open: {(time.perf_counter() - started) * 1000 / len(plans):.0f} ms per NEEM", flush=True)
    times: dict[str, list[float]] = {}

    def flushed(done: object, since: float) -> None:
        """Record when ``done`` (a group's future) resolves: its flush, on the syncer's thread."""
        done.add_done_callback(  # type: ignore[attr-defined]
            lambda _: times.setdefault("flush (syncer's thread)", []).append((time.perf_counter() - since) * 1000))

    def step(neem: str, row: object) -> None:
        # as the situation's job does it alone (routes.situation): its imagining written and
        # committed first, so the syncer flushes while the engine ranks
        group, marks = ctx.thread.group, [time.perf_counter()]
        assert group is not None
        done = group.join()
        session = ctx.engine.session(neem)
        available = [str(c) for c in row.available or (row.action,)]  # type: ignore[attr-defined]
        at = row.time.isoformat()  # type: ignore[attr-defined]
        found = session.offer(available, at)
        session.write_imagined(found)
        marks.append(time.perf_counter())
        group.commit()
        marks.append(time.perf_counter())
        flushed(done, marks[-1])
        ranking, ms = session.rank(found)
        session.describe(found, ranking, ms)
        routine_now(ctx.engine, session, found.when.seconds)
        marks.append(time.perf_counter())
        group.join(linger=10.0)
        session.write_ranking(found, ranking)
        marks.append(time.perf_counter())
        done = group.join()
        end = row.end.isoformat() if row.end is not None else None  # type: ignore[attr-defined]
        session.log(str(row.action), at, end)  # type: ignore[attr-defined]
        marks.append(time.perf_counter())
        group.commit()
        marks.append(time.perf_counter())
        flushed(done, marks[-1])
        session.warm.warm(session.ranker, session.ranker.last_end, stored_reader(ctx.engine, session))
        marks.append(time.perf_counter())
        for name, (a, b) in zip(("situation written", "its commit", "situation ranked (chain, routine)",
                                 "ranking written back", "action", "its commit 2", "warm-up after the action"),
                                zip(marks, marks[1:])):
            times.setdefault(name, []).append((b - a) * 1000)
        times.setdefault("robot-step", []).append((marks[-1] - marks[0]) * 1000)

    try:
        for round_ in range(STEPS):
            if round_ == WARM_ROUNDS:
                times.clear()
            for neem, _, todo in plans:
                ctx.thread.call(step, neem, todo[round_])
    finally:
        ctx.thread.close()
    print(f"{robots} robots, {STEPS - WARM_ROUNDS} steps each; load average {os.getloadavg()[0]:.1f}"
          " (the flushes run beside the engine thread, not in the robot-step)", flush=True)
    for name, values in times.items():
        values.sort()
        print(f"  {name:26s} p50 {percentile(values, 50):7.2f}  p99 {percentile(values, 99):7.2f}"
              f"  mean {sum(values) / len(values):7.2f} ms", flush=True)
    mean = sum(times["robot-step"]) / len(times["robot-step"])
    print(f"  one engine thread: at most {1000 / mean:.0f} robot-steps a second", flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]), Path(sys.argv[2]) if len(sys.argv) > 2 else Path("/tmp/neem-hub-engine"))
