"""``python -m oracle rank``: rank the tasks available now from the NEEM's history, write it back."""

from __future__ import annotations

import argparse
import json
from dataclasses import replace

from oracle.commands.common import AT, JSON, METHOD, NEEM, ONTOLOGY_OPTIONS, SETTINGS, STORE, add_options



def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser("rank", help="rank the available tasks and predict the chain (writes the ranking back)")
    add_options(parser, STORE, NEEM)
    parser.add_argument("--available", nargs="+", metavar="CALL",
                        help="rank these calls (e.g. 'pick(red_mug)') instead of the latest imagined situation "
                             "(a NEEM that imagined nothing: the actions done so far)")
    add_options(parser, AT, METHOD, SETTINGS)
    parser.add_argument("--no-write", "--dry-run", dest="no_write", action="store_true",
                        help="write nothing into the NEEM (a ranking of --available without --at, a what-if at "
                             "the present moment, is never written)")
    parser.add_argument("--prior", metavar="PRIOR.json",
                        help="rank with this shared prior ('prior build'; default: the store's own, STORE.prior.json "
                             "beside a SQLite store, if there is one; 'none': without)")
    add_options(parser, JSON, *ONTOLOGY_OPTIONS)
    parser.set_defaults(handler=run)


def _joined(note: str | None, more: str) -> str:
    return more if note is None else f"{note}; {more}"


def run(args: argparse.Namespace) -> int:
    from oracle.commands.common import method_from, moment_from, settings_from
    from oracle.commands.target import connect
    from oracle.commands.shown import print_ranking
    from oracle.ranking import finite, rank_neem, support_fields

    settings = settings_from(args.settings)
    method = method_from(args)
    at = moment_from(args.at)  # before the store is opened: a bad --at touches nothing
    # --available without --at asks "what if these were offered now?": a preference dated today
    # in a NEEM recorded long ago would be a false record, so that exploration writes nothing
    exploring = args.available is not None and at is None
    write = not args.no_write and not exploring
    bridge, onto = connect(args, write=write)
    from oracle.algorithm.prior import find_prior

    prior = find_prior(args.prior, bridge.store.location, onto)
    result = rank_neem(bridge, onto, settings, args.available, at, write=write, method=method, prior=prior)
    if exploring and not args.no_write:
        result = replace(result, note=_joined(result.note, "not written: --available without --at ranks a what-if "
                                                            "at the present moment (give --at to record a decision)"))
    if args.json:
        print(json.dumps({
            "neem": result.neem, "method": result.method, "at": result.at, "time_of_day": result.time_of_day,
            "history": result.history, "ms": result.milliseconds,
            "ranking": [{"rank": t.rank, "call": str(c), "score": finite(t.score), "similar": t.n_similar,
                         **support_fields(t), "mode": u.mode, "mode_support": {"context": u.context, "counts": u.counts},
                         **({"people": p} if p else {})}
                        for t, c, u, p in zip(result.ranking, result.calls, result.usual,
                                              result.people or (None,) * len(result.calls))],
            "chain": [str(c) for c in result.chain], "chain_modes": list(result.chain_modes),
            "written": result.written, "note": result.note,
        }, indent=1))
        return 0
    print_ranking(result, modes=True)  # who usually does each task and step (thesis 6.3)
    return 0
