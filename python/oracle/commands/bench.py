"""``python -m oracle bench``: run the benchmarks and print (and optionally save) their figures."""

from __future__ import annotations

from typing import Any

import argparse
import importlib
import importlib.util
import json
from pathlib import Path

from oracle.benchmarks import AREAS
from oracle.errors import NeemOracleError


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser("bench", help="run the benchmarks and print their figures")
    parser.add_argument("--json", type=Path, metavar="FILE", help="also write {'rows': [...]} to FILE")
    parser.add_argument("--only", choices=AREAS, action="append", help="run only these areas")
    parser.add_argument("--quick", action="store_true", help="smaller sizes, for a smoke run")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    rows: list[dict[str, Any]] = []
    for area in args.only or AREAS:
        name = f"oracle.benchmarks.{area}"
        if importlib.util.find_spec(name) is None:
            continue
        print(f"== {area} ==", flush=True)
        rows.extend(importlib.import_module(name).run(quick=args.quick))
    if args.json is not None:
        try:
            from oracle.files import write_private_bytes

            write_private_bytes(args.json, (json.dumps({"rows": rows}, indent=2) + "\n").encode())  # 0600, as every file
        except OSError as error:
            raise NeemOracleError(f"{args.json}: cannot write ({error.strerror})") from None
    return 0
