"""``python -m oracle rank``: rank the tasks available now from the NEEM's history, write it back."""

from __future__ import annotations

import argparse
import json
import math
from datetime import datetime

from oracle.commands.common import add_ontology_options


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser("rank", help="rank the available tasks and predict the chain (writes the ranking back)")
    parser.add_argument("--store", help="store: a SQLite path, sqlite:///PATH or mongodb://... (default: the user's store)")
    parser.add_argument("--neem", help="NEEM id (needed when the store holds several)")
    parser.add_argument("--available", nargs="+", metavar="CALL",
                        help="rank these calls (e.g. 'pick(red_mug)') instead of the latest imagined situation")
    parser.add_argument("--at", help="time of the decision for --available: ISO-8601 or unix seconds (default: now)")
    parser.add_argument("--settings", default="recommended",
                        help="settings YAML, 'recommended' or a thesis Fig. 5.5 letter (default: recommended)")
    parser.add_argument("--no-write", action="store_true", help="do not write the ranking back into the NEEM")
    parser.add_argument("--json", action="store_true", help="print the ranking as JSON")
    add_ontology_options(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from oracle.commands.evaluate import settings_from
    from oracle.commands.prolog import _connect, _parse_time
    from oracle.ranking import finite, rank_neem

    settings = settings_from(args.settings)
    at = _parse_time(args.at) if args.at is not None else None
    bridge, onto = _connect(args, write=not args.no_write)
    result = rank_neem(bridge, onto, settings, args.available, at, write=not args.no_write)
    if args.json:
        print(json.dumps({
            "neem": result.neem, "at": result.at, "time_of_day": result.time_of_day, "history": result.history,
            "ms": result.milliseconds,
            "ranking": [{"rank": t.rank, "call": str(c), "score": finite(t.score), "similar": t.n_similar}
                        for t, c in zip(result.ranking, result.calls)],
            "chain": [str(c) for c in result.chain], "written": result.written, "note": result.note,
        }, indent=1))
        return 0
    print_ranking(result)
    return 0


def print_ranking(result, limit: int | None = None) -> None:  # noqa: ANN001
    when = datetime.fromtimestamp(result.at).isoformat(timespec="seconds")
    print(f"NEEM {result.neem}: {result.history} past actions, decision at {when} ({result.time_of_day}); "
          f"ranked {len(result.calls)} options in {result.milliseconds:.2f} ms")
    shown = list(zip(result.ranking, result.calls))[:limit]
    for t, call in shown:
        score = "no similar history" if math.isinf(t.score) else f"score {t.score:.4f} from {t.n_similar} similar"
        print(f"  {t.rank:2d}. {str(call):32s} {score}")
    if limit is not None and len(result.calls) > limit:
        print(f"  ... and {len(result.calls) - limit} more")
    print("predicted chain: " + " -> ".join(str(c) for c in result.chain))
    if result.written is not None:
        print(f"ranking written back as {result.written}")
    if result.note is not None:
        print(result.note)
