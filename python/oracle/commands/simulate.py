"""``python -m oracle simulate --serve URL --persona N``: a simulated robot driving the service.

The robot lives in the kitchen world (oracle.world) with one persona: each simulated step it
posts what it perceives and the tasks available, the persona's choice as the tablet would, and
the action it then executes, as EDAN's framework would. ``--robots N`` runs N robots at once (one NEEM each) for a load test.
"""

from __future__ import annotations

import argparse
import threading
import time
from urllib.parse import quote


#: Seconds between steps when a person follows along on the tablet.
WATCHABLE_S = 3.0


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser("simulate", help="a simulated robot (kitchen world + persona) driving a running service")
    parser.add_argument("--serve", required=True, metavar="URL", help="the service, e.g. http://127.0.0.1:8765")
    parser.add_argument("--persona", type=int, default=0, help="which persona of the world's generator (default 0)")
    parser.add_argument("--seed", type=int, default=3, help="the generator's seed (default 3, as make demo)")
    parser.add_argument("--days", type=int, default=2, help="simulated days to drive (default 2)")
    parser.add_argument("--neem", help="NEEM to log into (default: a new one named after the persona)")
    parser.add_argument("--robots", type=int, default=1, help="robots at once, one NEEM each (default 1)")
    parser.add_argument("--delay", type=float, default=0.0, help="seconds between steps, to watch the page (default 0)")
    parser.add_argument("--follow-tablet", action="store_true",
                        help="do what the person chooses on the tablet (waiting --wait s for it) instead of the persona's choice")
    parser.add_argument("--wait", type=float, default=60.0, metavar="S",
                        help="with --follow-tablet: how long to wait for a choice before doing the persona's (default 60)")
    parser.add_argument("--pace", type=float, default=None, metavar="S",
                        help="seconds between steps (default: --delay; with --follow-tablet 3 s, a pace a person can watch)")
    parser.add_argument("--token", help="the service's token, if it has one")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from oracle.errors import NeemOracleError
    from oracle.service.robot import Drive, drive, percentile, persona_rows

    from oracle.service.client import Client

    if args.robots < 1 or args.days < 1:
        raise NeemOracleError("--robots and --days must be at least 1")
    Client(args.serve).close()  # a malformed URL is one error line, before any thread starts
    if args.follow_tablet and args.robots != 1:
        raise NeemOracleError("--follow-tablet drives one robot: drop --robots")
    pace = args.pace if args.pace is not None else (WATCHABLE_S if args.follow_tablet and not args.delay else args.delay)
    if pace < 0 or args.wait <= 0:
        raise NeemOracleError("--pace must be 0 or more and --wait more than 0 seconds")
    results: list[Drive] = [Drive() for _ in range(args.robots)]

    def one(index: int) -> None:
        neem = args.neem if args.robots == 1 else (f"{args.neem}-{index}" if args.neem else None)
        user, rows = persona_rows(args.persona + index, args.seed, args.days)
        results[index] = drive(args.serve, user, rows, neem, args.token, pace, announce=show,
                               follow=args.wait if args.follow_tablet else None)

    def show(neem: str) -> None:
        print(f"driving NEEM {neem}: the page is {args.serve.rstrip('/')}/?neem={quote(neem, safe='')}", flush=True)

    started = time.perf_counter()
    threads = [threading.Thread(target=one, args=(i,)) for i in range(args.robots)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    seconds = time.perf_counter() - started
    steps = sum(r.steps for r in results)
    errors = [e for r in results for e in r.errors]
    print(f"{args.robots} robot(s) drove {steps} steps in {seconds:.1f} s; {len(errors)} errors")
    for kind in ("perception", "situation", "server", "rank", "choice", "action"):
        values = sorted(v for r in results for v in r.latencies.get(kind, []))
        if values:
            print(f"  {kind:10s} n={len(values):5d}  p50 {percentile(values, 50):6.2f} ms  p99 {percentile(values, 99):6.2f} ms")
    for error in errors[:5]:
        print(f"  error: {error}")
    return 1 if errors else 0
