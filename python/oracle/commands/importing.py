"""``import``: log action chains (JSONL) into a store, one NEEM per user."""

from __future__ import annotations

import argparse
import contextlib
import signal
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING

from oracle.commands.common import NUMBERS, ONTOLOGY_OPTIONS, STORE, add_options, bounded_int, ontology_from
from oracle.errors import NeemOracleError

if TYPE_CHECKING:
    from oracle.ontology import OdbOntology
    from oracle.store import Store


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser("import", help="log action chains (JSONL) as one NEEM per user")
    parser.add_argument("chains", type=Path, metavar="CHAINS.jsonl")
    add_options(parser, STORE, NUMBERS, *ONTOLOGY_OPTIONS)
    which = parser.add_mutually_exclusive_group()
    which.add_argument("--replace", action="store_true",
                       help="replace the NEEM of a user who has one (default: refuse that user, import the others)")
    which.add_argument("--as-new", action="store_true", help="add a new NEEM for a user who has one")
    parser.add_argument("--session", action="store_true",
                        help="log into temporary NEEMs, wiping earlier temporary ones (keep them with 'persist')")
    parser.add_argument("--no-clock", action="store_true",
                        help="the rows have no times (e.g. EGTEA): log each user's actions in file order on a sequence clock, "
                             "with no part of the day (docs/time.md)")
    parser.add_argument("--commit-every", type=bounded_int(1, 1_000_000), default=100, metavar="N",
                        help="actions per transaction (1 = each action durable before the next; default 100)")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from oracle.neem.importing import check_chains, import_chains
    from oracle.store import open_store

    onto = ontology_from(args)
    checked = check_chains(onto, args.chains, no_clock=args.no_clock)  # before the store is opened: a bad file creates nothing
    with open_store(args.store, number_format=args.numbers) as store, _first_ctrl_c_between_rows() as stop:
        report: dict[str, int] = {}
        refused: list[str] = []
        existing = "replace" if args.replace else "new" if args.as_new else "refuse"
        try:
            import_chains(store, onto, args.chains, report=report, commit_every=args.commit_every, session=args.session,
                          checked=checked, no_clock=args.no_clock, stop=stop, existing=existing, refused=refused)
        except NeemOracleError:
            _print(report, store)
            raise
        except KeyboardInterrupt:
            _print(report, store)
            print(f"interrupted: {sum(report.values())} actions committed", file=sys.stderr)
            return 130
        _print(report, store)
        _keep(store, onto, report)
    for line in refused:
        print(line, file=sys.stderr)
    return 1 if refused else 0


def _keep(store: Store, onto: OdbOntology, report: dict[str, int]) -> None:
    """What the first rank of each imported NEEM needs, kept in the store (oracle.ranking.keep_neem):
    an optimisation, so a failure only leaves that rank to read and fit everything."""
    from oracle.ranking import keep_neem

    public = {info.id for info in store.neems()}
    for neem_id in report:
        if neem_id in public:
            try:
                keep_neem(store, onto, neem_id)
            except NeemOracleError:
                continue


@contextlib.contextmanager
def _first_ctrl_c_between_rows() -> Iterator[Callable[[], bool]]:
    """The first Ctrl-C is noted and acted on between two rows (so the count printed is what
    the store holds); a second one interrupts at once."""
    pressed: list[bool] = []

    def note(signum: int, frame: object) -> None:
        pressed.append(True)
        signal.signal(signal.SIGINT, signal.default_int_handler)

    try:
        previous = signal.signal(signal.SIGINT, note)
    except ValueError:  # not the main thread: Ctrl-C is not ours to handle
        yield lambda: False
        return
    try:
        yield lambda: bool(pressed)
    finally:
        signal.signal(signal.SIGINT, previous)


def _print(report: dict[str, int], store: Store) -> None:
    """Each NEEM's id, name and committed actions (a NEEM still hidden has its name in staging)."""
    from oracle.store.staging import STAGING
    from oracle.store.ids import ALIAS_KEY, alias_of

    names = {info.id: alias_of(info) for info in store.neems()}
    names.update((str(info.meta.get(STAGING)), info.meta.get(ALIAS_KEY)) for info in store.staging_neems())
    for neem_id, count in report.items():
        print(f"{neem_id}\t{names.get(neem_id) or '-'}\t{count} actions")
