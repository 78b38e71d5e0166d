"""``import``: log action chains (JSONL) into a store, one NEEM per user."""

from __future__ import annotations

import argparse
import contextlib
import signal
import sys
from collections.abc import Callable, Iterator, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from oracle.commands.common import NUMBERS, ONTOLOGY_OPTIONS, STORE, add_options, bounded_int, ontology_from
from oracle.errors import NeemOracleError

if TYPE_CHECKING:
    from oracle.ontology import OdbOntology
    from oracle.store import Store
    from oracle.writtenview import WrittenView


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
    from oracle.progress import bar
    from oracle.store import open_store

    onto = ontology_from(args)
    lines = _lines(args.chains)
    with bar(f"checking {args.chains.name}", "rows", lines) as tick:
        # before the store is opened: a bad file creates nothing
        checked = check_chains(onto, args.chains, no_clock=args.no_clock, progress=tick)
    rows = sum(plan.rows for plan in checked.plans.values())
    with open_store(args.store, number_format=args.numbers) as store:
        report: dict[str, int] = {}
        refused: list[str] = []
        views: dict[str, WrittenView] = {}  # each user's history view, as the import writes it
        existing = "replace" if args.replace else "new" if args.as_new else "refuse"
        try:
            with _first_ctrl_c_between_rows() as pressed, bar("logging", "actions", rows) as tick:
                logged = [0]

                def stop() -> bool:  # asked before each row: the row count is the progress
                    tick(logged[0], rows)
                    logged[0] += 1
                    return pressed()

                import_chains(store, onto, args.chains, report=report, commit_every=args.commit_every,
                              session=args.session, checked=checked, no_clock=args.no_clock, stop=stop,
                              existing=existing, refused=refused, views=views)
                tick(rows, rows)
        except NeemOracleError:
            _print(report, store)
            raise
        except KeyboardInterrupt:
            _print(report, store)
            print(f"interrupted: {sum(report.values())} rows committed (an unfinished NEEM is listed as"
                  " INCOMPLETE by 'neems')", file=sys.stderr)
            return 130
        _print(report, store)
        try:
            del checked  # the parsed rows (13 MiB at 50,000 actions) are not held through the fits
            _keep(store, onto, report, views)
        except KeyboardInterrupt:
            # the NEEMs are complete; only the kept fit (an optimisation) is left for the first rank
            print("interrupted: every NEEM is imported; its first rank will read and fit it", file=sys.stderr)
            return 130
    if refused:  # one line, as every refusal (the other users are imported)
        shown = "; ".join(refused[:3]) + (f"; and {len(refused) - 3} more" if len(refused) > 3 else "")
        print(f"error: {shown}" if len(refused) == 1 else f"error: {len(refused)} users not imported: {shown}",
              file=sys.stderr)
    return 1 if refused else 0


def _lines(path: Path) -> int | None:
    """The file's line count, the check's total (None when it cannot be read: the check says why)."""
    from oracle.errors import ChainSyntaxError
    from oracle.handed import Handed, open_handed

    # Counted in chunks of a regular file only: a FIFO or a device is left to the check, which
    # refuses it (a line count of /dev/zero would never end).
    try:
        with open_handed(path, Handed("chains", ChainSyntaxError)) as handle:
            return sum(chunk.count(b"\n") for chunk in iter(lambda: handle.read(1 << 20), b""))
    except (OSError, ChainSyntaxError):
        return None


def _keep(store: Store, onto: OdbOntology, report: dict[str, int], views: Mapping[str, WrittenView]) -> None:
    """What the first rank of each imported NEEM needs, kept in the store (oracle.ranking.keep_neem):
    an optimisation, so a failure only leaves that rank to read and fit everything. Ctrl-C is
    honoured here (a KeyboardInterrupt): a fit cut short keeps nothing."""
    from oracle.progress import bar
    from oracle.ranking import keep_neem
    from oracle.trim import give_back
    from oracle.writtenview import keep_written

    give_back(store)  # the writes' memory returned before the fits: their peaks do not add up
    public = {info.id for info in store.neems()}
    kept = [neem_id for neem_id in report if neem_id in public]
    with bar("fitting for the first rank", "NEEMs", len(kept)) as tick:
        for done, neem_id in enumerate(kept):
            tick(done, len(kept))
            try:
                keep_written(store, onto, neem_id, views)  # the view as written: no read through Prolog
                keep_neem(store, onto, neem_id)
            except NeemOracleError:
                continue
        tick(len(kept), len(kept))


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
    """Each NEEM's id, name and actions as ``neems`` counts them: the rows committed and the
    breaks between them that the logger wrote as idle actions (a NEEM still hidden, cut short,
    has its name in staging and only its rows counted)."""
    from oracle.neem.query import summarize_neem
    from oracle.store.staging import STAGING
    from oracle.store.ids import ALIAS_KEY, alias_of

    infos = {info.id: info for info in store.neems()}
    names = {neem_id: alias_of(info) for neem_id, info in infos.items()}
    names.update((str(info.meta.get(STAGING)), info.meta.get(ALIAS_KEY)) for info in store.staging_neems())
    for neem_id, count in report.items():
        total = summarize_neem(store, neem_id, infos[neem_id]).actions if neem_id in infos else count
        idle = total - count
        breaks = f" ({count} rows and {idle} break{'s' if idle != 1 else ''}, logged as idle actions)" if idle > 0 else ""
        print(f"{neem_id}\t{names.get(neem_id) or '-'}\t{total} action{'s' if total != 1 else ''}{breaks}")
