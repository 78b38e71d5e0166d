"""``python -m oracle prolog | why-not | what-next | something-else``: the Prolog side."""

from __future__ import annotations

import argparse
import json
from datetime import datetime

from oracle.commands.common import add_ontology_options
from oracle.errors import NeemOracleError


def register(subparsers: argparse._SubParsersAction) -> None:
    top = subparsers.add_parser("prolog", help="interactive SWI-Prolog toplevel with the NEEM store connected")
    _common(top)
    top.set_defaults(handler=run_toplevel)

    why = subparsers.add_parser("why-not", help="why the robot did not do a task (thesis 4.6)")
    why.add_argument("task", help="task call in chain syntax, e.g. 'pick(banana)'")
    why.add_argument("--at", help="time asked about: ISO-8601 or unix seconds (default: the latest decision)")
    _common(why)
    why.set_defaults(handler=run_why_not)

    nxt = subparsers.add_parser("what-next", help="the predicted next tasks from the latest imagined preference")
    _common(nxt)
    nxt.set_defaults(handler=run_what_next)

    alt = subparsers.add_parser("something-else", help="the next best alternative to the current or a proposed task")
    alt.add_argument("task", nargs="?", help="proposed task call (default: the task of the latest action)")
    _common(alt)
    alt.set_defaults(handler=run_something_else)


def _common(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--store", help="store: a SQLite path, sqlite:///PATH or mongodb://... (default: the user's store)")
    parser.add_argument("--neem", help="NEEM id (needed when the store holds several)")
    parser.add_argument("--json", action="store_true", help="print the answer as JSON")
    add_ontology_options(parser)


def _connect(args: argparse.Namespace, *, write: bool = False):  # noqa: ANN202
    from oracle.bridge import Bridge
    from oracle.commands.target import open_target

    target = open_target(args, write=write)
    return Bridge(target.store, target.neem_id, target.onto), target.onto


def _parse_task(text: str, onto) -> tuple[str, list[str]]:  # noqa: ANN001
    from oracle.chains import parse_call

    call = parse_call(text)
    onto.task_iri(call.task)
    for arg in call.args:
        onto.object_iri(arg)
    return call.task, list(call.args)


def _parse_time(text: str | None) -> float | None:
    """Unix seconds of ``--at`` under the one time rule (oracle.timeline), inside the range a
    store holds: ``nan``, ``inf`` or ``1e20`` are refused before anything reaches Prolog."""
    from oracle.timeline import TimeValueError, parse_moment

    if text is None:
        return None
    try:
        return parse_moment(text)
    except TimeValueError as error:
        raise NeemOracleError(f"--at {error}") from None


def run_toplevel(args: argparse.Namespace) -> int:
    bridge, _ = _connect(args, write=True)  # a query typed at the toplevel may assert facts
    print(f"% NEEM {bridge.neem_id} of {bridge.store.location}; KnowRob predicates loaded (halt. or EOF to leave)")
    bridge.query("prolog")
    return 0


def run_why_not(args: argparse.Namespace) -> int:
    from oracle.answers import why_not_sentence

    bridge, onto = _connect(args)
    task, objs = _parse_task(args.task, onto)
    answer = bridge.why_not(task, objs, _parse_time(args.at))
    print(json.dumps(answer, indent=2) if args.json else why_not_sentence(answer))
    return 0


def run_what_next(args: argparse.Namespace) -> int:
    from oracle.answers import what_next_sentence

    bridge, _ = _connect(args)
    answer = bridge.what_next()
    print(json.dumps(answer, indent=2) if args.json else what_next_sentence(answer))
    return 0


def run_something_else(args: argparse.Namespace) -> int:
    from oracle.answers import something_else_sentence

    bridge, onto = _connect(args)
    if args.task:
        task, objs = _parse_task(args.task, onto)
        answer = bridge.something_else(task, objs)
    else:
        answer = bridge.something_else()
    print(json.dumps(answer, indent=2) if args.json else something_else_sentence(answer))
    return 0
