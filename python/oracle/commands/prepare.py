"""``python -m oracle prepare``: the few things worth preparing now for the user's coming routines
(docs/beyond.md)."""

from __future__ import annotations

import argparse
import json
from typing import Any

from oracle.commands.common import AT, JSON, NEEM, ONTOLOGY_OPTIONS, STORE, add_options, moment_from

from oracle.commands.target import connect

PARTS = {"morning": "Morning", "midday": "Midday", "evening": "Evening", "night": "Night"}


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser(
        "prepare", help="the objects worth preparing for the user's coming routines, each with its reason",
        description="From the routines the user usually begins in the coming part of the day (--for; default: the "
        "part after now's), the objects they need, most needed first, with where the NEEM last had them and their state "
        "(used and not washed since, in the dishwasher, washed).")
    parser.add_argument("--for", dest="part", choices=sorted(PARTS), help="the part of the day to prepare for")
    AT.add(parser)
    add_options(parser, STORE, NEEM, JSON, *ONTOLOGY_OPTIONS)
    parser.set_defaults(handler=run)


def state_said(state: dict[str, Any]) -> str:
    """The object's state as the end of its line (nothing when unknown)."""
    from oracle.past.prepare import IN_WASHER, USED, WASHED
    from oracle.timeline import clock

    if state["since"] is None:
        return ""
    when = f"{clock(state['since']):%Y-%m-%d %H:%M}"
    said = {USED: f"used in {state['action']} on {when} and not washed since: worth washing now",
            IN_WASHER: f"in the dishwasher since {when}, not yet washed: worth running it",
            WASHED: f"washed (the dishwasher ran on {when})"}
    return f"; {said[state['state']]}" if state["state"] in said else ""


def run(args: argparse.Namespace) -> int:
    from oracle.past.mine import neem_preparation
    from oracle.timeline import clock

    bridge, _ = connect(args)
    moment = moment_from(args.at)
    found = neem_preparation(bridge, PARTS[args.part] if args.part else None, None if moment is None else moment.seconds)
    if args.json:
        print(json.dumps(found, indent=2, ensure_ascii=False))
        return 0
    if not found["prepare"]:
        print(f"nothing to prepare for the {str(found['for']).lower()}: no routine of the user's begins then")
        return 0
    print(f"for the {found['for'].lower()}:")
    for item in found["prepare"]:
        used = item["last_used"]
        where = f"; last used in {used['task']} on {clock(used['time']):%Y-%m-%d %H:%M}" if used else ""
        print(f"  {item['object']}: {item['reason']}{where}{state_said(item['state'])}")
    return 0
