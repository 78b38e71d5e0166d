"""``export``, ``load``, ``neems`` and ``persist``: moving NEEMs in and out of a store."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from oracle.commands.common import JSON, NUMBERS, STORE, add_options


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    export = subparsers.add_parser("export", help="write NEEMs in the mongodump layout KnowRob's remember/1 reads")
    add_options(export, STORE, NUMBERS)
    export.add_argument("--neem", metavar="ID", help="the NEEM to export (default: every NEEM, one folder each)")
    export.add_argument("--out", type=Path, required=True, metavar="DIR")
    export.add_argument("--hub", action="store_true",
                        help="the NEEM hub's layout: collections <id>_triples etc. in database 'neems' (openEASE)")
    export.add_argument("--visibility", choices=("public", "private"), default=None,
                        help="the registry entry's visibility on a NEEM hub (default: private, said on stderr)")
    export.add_argument("--url", metavar="URL",
                        help="the NEEM's repository in the hub's registry entry, where openEASE's overview page reads its"
                             " README.md (default: https://neemgit.informatik.uni-bremen.de/neems/<name>, the hub's place)")
    export.add_argument("--soma", type=Path, metavar="DIR",
                        help="folder with SOMA.owl, DUL.owl, SOMA-HOME.owl: their whole graphs go into the NEEM")
    export.set_defaults(handler=run_export)

    load = subparsers.add_parser("load", help="load NEEM dumps (ours or openEASE/KnowRob ones) into the store")
    add_options(load, STORE, NUMBERS)
    load.add_argument("dir", type=Path, metavar="DIR")
    load.add_argument("--neem", metavar="ID", help="id to load a single NEEM under")
    load.add_argument("--replace", action="store_true", help="replace NEEMs that already exist")
    load.set_defaults(handler=run_load)

    neems = subparsers.add_parser("neems", help="list the NEEMs of a store with user, actions and time span")
    add_options(neems, STORE, NUMBERS, JSON)
    neems.set_defaults(handler=run_neems)

    persist = subparsers.add_parser("persist", help="keep a temporary session NEEM under a name")
    add_options(persist, STORE, NUMBERS)
    persist.add_argument("--neem", required=True, metavar="ID")
    persist.add_argument("--as", dest="name", required=True, metavar="NAME")
    persist.set_defaults(handler=run_persist)


def run_export(args: argparse.Namespace) -> int:
    from oracle.store import open_store
    from oracle.progress import bar
    from oracle.store.dump import export_neem
    from oracle.store.mongo import DEFAULT_DB
    from oracle.store.ids import resolve_neem

    import sys

    from oracle.errors import StoreError

    files: list[Path] = []
    if args.soma is not None:
        files = [args.soma / name for name in ("SOMA.owl", "DUL.owl", "SOMA-HOME.owl")]
        missing = [str(f) for f in files if not f.is_file()]
        if missing:
            names = ", ".join(Path(m).name for m in missing)
            raise StoreError(f"{args.soma}: no {names} there (--soma names the folder of the official files)")
    if args.url is not None and (args.neem is None or not args.url.startswith(("http://", "https://"))):
        raise StoreError("--url names one NEEM's repository: an http(s) URL, with --neem" if args.neem is None else
                         f"--url {args.url!r}: openEASE reads a NEEM's repository over http(s)")
    options = {"db_name": "neems" if args.hub else DEFAULT_DB, "hub_prefix": args.hub,
               "visibility": args.visibility == "public", "ontology_files": files, "url": args.url}
    with open_store(args.store, number_format=args.numbers, read_only=True) as store:
        ids = [resolve_neem(store, args.neem)] if args.neem is not None else [info.id for info in store.neems()]
        written: list[str] = []
        with bar("exporting", "NEEMs", len(ids)) as tick:
            for done, neem_id in enumerate(ids):  # as export_all, one folder each, with its progress
                tick(done, len(ids))
                folder = args.out if args.neem is not None else args.out / neem_id
                counts = export_neem(store, neem_id, folder, **options)
                written.append(f"{neem_id}: {counts['triples']} triples -> {folder}")
            tick(len(ids), len(ids))
        print("\n".join(written))
    # said after the export succeeded: a failed one prints its one error line only
    if args.soma is None:
        print("hint: the NEEM carries the SOMA/DUL extract it was logged with; --soma DIR writes the whole graphs"
              " (a read-only KnowRob such as openEASE loads no ontology)", file=sys.stderr)
    if args.visibility is None:
        print("hint: registry entry written private (visibility: false); --visibility public lists it on a NEEM hub",
              file=sys.stderr)
    return 0


def run_load(args: argparse.Namespace) -> int:
    from oracle.neem.query import summarize_neem
    from oracle.progress import bar
    from oracle.store import open_store
    from oracle.store.dump import load_dump

    with open_store(args.store, number_format=args.numbers) as store, bar("loading", "documents") as tick:
        loaded = load_dump(store, args.dir, neem_id=args.neem, replace=args.replace, progress=tick)
    with open_store(args.store, number_format=args.numbers) as store:
        for neem_id in loaded:
            summarize_neem(store, neem_id)  # kept in the registry: listings need not count again
            print(neem_id)
    return 0


def _iso(seconds: float | None, clocked: bool = True) -> str | None:
    """A time of the listing; in a NEEM without a clock (oracle.timeline), its position."""
    from oracle.timeline import format_clock

    if seconds is None:
        return None
    return format_clock(seconds) if clocked else f"position {seconds:g}"


def run_neems(args: argparse.Namespace) -> int:
    from oracle.neem.importing import INCOMPLETE_KEY
    from oracle.neem.query import summarize_neem
    from oracle.store import open_store
    from oracle.timeline import has_clock

    # Read-only: a listing never waits for a writer. A NEEM whose kept summary is stale (a
    # load, a bare insert) is counted from its triples; 'load' keeps the summary of what it loads.
    with open_store(args.store, number_format=args.numbers, read_only=True) as store:
        infos = list(store.neems())
        rows = [summarize_neem(store, info.id) for info in infos]
    clocked = {info.id: has_clock(info.meta) for info in infos}
    cut = {info.id for info in infos if info.meta.get(INCOMPLETE_KEY)}
    if args.json:
        print(json.dumps([{**row.__dict__, "begin": _iso(row.begin, clocked[row.id]), "end": _iso(row.end, clocked[row.id]),
                           "incomplete": row.id in cut} for row in rows], indent=2))
        return 0
    wid = max([4] + [len(row.id) for row in rows])
    wname = max([4] + [len(row.name or "-") for row in rows])
    wuser = max([4] + [len(row.user or "-") for row in rows])
    print(f"{'NEEM':<{wid}}  {'name':<{wname}}  {'user':<{wuser}}  {'actions':>7}  {'begin':<25}  {'end':<25}  kept")
    for row in rows:
        print(
            f"{row.id:<{wid}}  {row.name or '-':<{wname}}"
            f"  {row.user or '-':<{wuser}}  {row.actions:>7}  {_iso(row.begin, clocked[row.id]) or '-':<25}"
            f"  {_iso(row.end, clocked[row.id]) or '-':<25}  {'no' if row.temporary else 'yes'}"
            + ("  INCOMPLETE (its import was cut; importing this user again replaces it)" if row.id in cut else "")
        )
    return 0


def run_persist(args: argparse.Namespace) -> int:
    from oracle.store import open_store

    with open_store(args.store, number_format=args.numbers, create=False) as store:
        from oracle.neem.lifecycle import persist

        info = persist(store, args.neem, args.name)
    print(info.id)
    return 0
