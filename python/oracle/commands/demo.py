"""``python -m oracle demo``: the main job on the embedded default store, in a few seconds.

Builds the sample kitchen ontology, logs five simulated days of one user into a NEEM named
``demo`` (replaced on every run), logs what is available on the sixth morning, ranks it from the
history through the Prolog bridge, writes the ranking back, and asks Prolog why a lower-ranked
task was not chosen.
"""

from __future__ import annotations

import argparse
import shlex
import time
from datetime import datetime
from typing import TYPE_CHECKING

from oracle.errors import NeemOracleError

if TYPE_CHECKING:
    from oracle.chains import ChainRow

from oracle.commands.common import METHOD, STORE, add_options, bounded_int, method_from

#: Registry mark of the NEEM the demo writes: it replaces only a NEEM carrying it.
DEMO_ORIGIN = "demo"


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser("demo", help="log a simulated user, rank the next task, answer why-not")
    add_options(parser, STORE)
    parser.add_argument("--days", type=bounded_int(1, 366), default=5, help="days of history to simulate, 1-366 (default 5)")
    parser.add_argument("--seed", type=bounded_int(0, 1_000_000), default=3, help="which simulated user (default 3)")
    add_options(parser, METHOD)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from oracle.algorithm.params import Hyperparameters
    from oracle.answers import why_not_sentence
    from oracle.bridge import Bridge
    from oracle.commands.shown import print_ranking
    from oracle.errors import NeemOracleError
    from oracle.commands.hints import runnable
    from oracle.neem.query import summarize_neem
    from oracle.neem.writer import NeemLogger
    from oracle.ontology import build_with_report
    from oracle.ranking import rank_neem
    from oracle.store import open_store
    from oracle.store.ids import find_neem, resolve_neem as find_neem_id
    from oracle.world.generate import simulate
    from oracle.world.personas import make_persona
    from oracle.world.worldfile import load_world

    method = method_from(args)
    if args.days < 1:
        raise NeemOracleError("--days must be at least 1")
    started = time.perf_counter()
    onto, report = build_with_report()
    print(f"1. ontology: sample kitchen, {report.n_objects} odb objects and {report.n_tasks} tasks under SOMA/DUL")

    persona = make_persona(args.seed, 0)
    rows, _ = simulate(persona, load_world(), args.days + 1, args.seed)
    last_day = _time(rows[-1]).date()
    history = [r for r in rows if _time(r).date() != last_day]
    now = next(r for r in rows if _time(r).date() == last_day)
    store = open_store(args.store)
    old = find_neem(store, "demo")
    if old is not None and old.meta.get("origin") != DEMO_ORIGIN:
        raise NeemOracleError(
            f"{store.location} already holds a NEEM 'demo' that the demo did not write; keep it: run the demo"
            " with --store OTHER.sqlite, or rename it first (persist --neem demo --as NAME)"
        )
    logger = NeemLogger.create(store, onto, user=persona.file_name, neem_id="demo", replace=True, commit_every=200,
                               meta={"origin": DEMO_ORIGIN})
    for row in history:
        logger.action(row.action, _time(row), row.end, available=row.available)
    logger.available(now.available or (), _time(now))
    logger.close()  # commits, and swaps the new demo NEEM in for the old one
    logged = summarize_neem(store, find_neem_id(store, "demo")).actions  # as 'neems' and 'rank' count them
    print(f"2. NEEM 'demo' in {store.location}: {logged} actions of {persona.file_name} over {args.days} days"
          f" ({len(history)} tasks and {logged - len(history)} breaks, logged as idle actions)")
    print(f"   ({persona.persona})")

    bridge = Bridge(store, "demo", onto)
    result = rank_neem(bridge, onto, Hyperparameters(), method=method)
    print(f"3. what the user may want now (they went on to do {now.action}):")
    print_ranking(result, limit=5)

    asked = result.calls[min(5, len(result.calls) - 1)]
    answer = bridge.why_not(asked.task, list(asked.args), result.at)
    print(f"4. why not {asked}?  {why_not_sentence(answer)}")
    print(f"done in {time.perf_counter() - started:.1f} s; try: {runnable()} prolog --neem demo"
          + (f" --store {shlex.quote(str(args.store))}" if args.store else ""))
    return 0


def _time(row: ChainRow) -> datetime:
    """The time of a simulated row (the generator gives every row one)."""
    if row.time is None:
        raise NeemOracleError(f"simulated row {row.action} has no time")
    return row.time
