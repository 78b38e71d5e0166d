"""``python -m oracle prolog | why-not | what-next | something-else``: the Prolog side."""

from __future__ import annotations

import argparse
import json
from typing import TYPE_CHECKING

from oracle.commands.common import AT, JSON, NEEM, ONTOLOGY_OPTIONS, STORE, add_options, connect, moment_from

if TYPE_CHECKING:
    from oracle.ontology import OdbOntology


def register(subparsers: argparse._SubParsersAction) -> None:
    top = subparsers.add_parser("prolog", help="interactive SWI-Prolog toplevel with the NEEM store connected")
    _common(top)
    top.set_defaults(handler=run_toplevel)

    why = subparsers.add_parser("why-not", help="why the robot did not do a task (thesis 4.6)")
    why.add_argument("task", help="task call in chain syntax, e.g. 'pick(banana)'")
    AT.add(why)
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
    add_options(parser, STORE, NEEM, JSON, *ONTOLOGY_OPTIONS)


def _parse_task(text: str, onto: OdbOntology) -> tuple[str, list[str]]:
    from oracle.chains import parse_call

    call = parse_call(text)
    onto.task_iri(call.task)
    for arg in call.args:
        onto.object_iri(arg)
    return call.task, list(call.args)


def run_toplevel(args: argparse.Namespace) -> int:
    bridge, _ = connect(args)
    print(f"% NEEM {bridge.neem_id} of {bridge.store.location}; KnowRob predicates loaded (halt. or EOF to leave)")
    bridge.query("prolog")
    return 0


def run_why_not(args: argparse.Namespace) -> int:
    from oracle.answers import why_not_sentence

    bridge, onto = connect(args)
    task, objs = _parse_task(args.task, onto)
    at = moment_from(args.at)
    answer = bridge.why_not(task, objs, None if at is None else at.seconds)
    print(json.dumps(answer, indent=2) if args.json else why_not_sentence(answer))
    return 0


def run_what_next(args: argparse.Namespace) -> int:
    from oracle.answers import what_next_sentence

    bridge, _ = connect(args)
    answer = bridge.what_next()
    print(json.dumps(answer, indent=2) if args.json else what_next_sentence(answer))
    return 0


def run_something_else(args: argparse.Namespace) -> int:
    from oracle.answers import something_else_sentence

    bridge, onto = connect(args)
    if args.task:
        task, objs = _parse_task(args.task, onto)
        answer = bridge.something_else(task, objs)
    else:
        answer = bridge.something_else()
    print(json.dumps(answer, indent=2) if args.json else something_else_sentence(answer))
    return 0
