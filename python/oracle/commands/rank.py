"""``python -m oracle rank``: rank the tasks available now from the NEEM's history, write it back."""

from __future__ import annotations

import argparse
import json
import math
import time
from datetime import datetime

from oracle.errors import LoggingError, NeemOracleError


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser("rank", help="rank the available tasks and predict the chain (writes the ranking back)")
    parser.add_argument("--store", help="store: a SQLite path, sqlite:///PATH or mongodb://... (default: the user's store)")
    parser.add_argument("--neem", help="NEEM id (default: the newest NEEM in the store)")
    parser.add_argument("--available", nargs="+", metavar="CALL",
                        help="rank these calls (e.g. 'pick(red_mug)') instead of the latest imagined situation")
    parser.add_argument("--at", help="time of the decision for --available: ISO-8601 or unix seconds (default: now)")
    parser.add_argument("--settings", default="recommended",
                        help="settings YAML, 'recommended' or a thesis Fig. 5.5 letter (default: recommended)")
    parser.add_argument("--no-write", action="store_true", help="do not write the ranking back into the NEEM")
    parser.add_argument("--json", action="store_true", help="print the ranking as JSON")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from oracle.algorithm.fast import PreferenceOracle
    from oracle.chains import parse_call
    from oracle.commands.evaluate import settings_from
    from oracle.commands.prolog import _connect, _parse_time
    from oracle.evaluation.replay import opening_tasks
    from oracle.logger import NeemLogger
    from oracle.situations import call_of, check_call, option_of, steps_from_history
    from oracle.timeofday import time_of_day

    settings = settings_from(args.settings)
    bridge, onto = _connect(args)
    history = bridge.history()
    if args.available:
        calls = [parse_call(text) for text in args.available]
        for call in calls:
            check_call(onto, call, "--available")
        at = _parse_time(args.at) if args.at is not None else time.time()
    else:
        latest = bridge.latest_situation()
        if latest is None:
            raise NeemOracleError(f"NEEM {bridge.neem_id!r} has no imagined situation to rank; pass --available CALL ...")
        calls = [parse_call(text) for text in latest["available"]]
        at = float(latest["begin"])
    past = [row for row in history if float(row["begin"]) < at]
    steps = steps_from_history(onto, past)
    oracle = PreferenceOracle.from_settings(onto.distances(), settings, opening_tasks(onto)).fit(steps)
    part = time_of_day(datetime.fromtimestamp(at))
    started = time.perf_counter()
    ranking = oracle.rank([option_of(onto, c) for c in calls], part)
    elapsed_ms = (time.perf_counter() - started) * 1000
    chain = [str(call_of(onto, option)) for option in ranking.chain()]
    written = None
    if not args.no_write:
        logger = NeemLogger(bridge.store, onto, bridge.neem_id)
        try:
            written = logger.preference([(call_of(onto, t.option), _finite(t.score)) for t in ranking], at)
        except LoggingError as error:
            written = f"not written: {error}"
    if args.json:
        print(json.dumps({
            "neem": bridge.neem_id, "at": at, "time_of_day": part, "history": len(steps), "ms": elapsed_ms,
            "ranking": [{"rank": t.rank, "call": str(call_of(onto, t.option)), "score": _finite(t.score),
                         "similar": t.n_similar} for t in ranking],
            "chain": chain, "written": written,
        }, indent=1))
        return 0
    print(f"NEEM {bridge.neem_id}: {len(steps)} past actions, decision at "
          f"{datetime.fromtimestamp(at).isoformat(timespec='seconds')} ({part}); ranked in {elapsed_ms:.2f} ms")
    for t in ranking:
        score = "no similar history" if math.isinf(t.score) else f"score {t.score:.4f} from {t.n_similar} similar"
        print(f"  {t.rank:2d}. {call_of(onto, t.option)!s:32s} {score}")
    print("predicted chain: " + " -> ".join(chain))
    if written is not None:
        print(f"ranking written back as {written}" if not str(written).startswith("not written") else written)
    return 0


def _finite(score: float) -> float:
    # JSON and the store need a number; an option without similar history scores as very large
    return score if math.isfinite(score) else 1e9
