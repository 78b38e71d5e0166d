"""``python -m oracle prolog | why-not | what-next | something-else``: the Prolog side."""

from __future__ import annotations

import argparse
import json
import sys
from typing import TYPE_CHECKING

from oracle.commands.common import AT, JSON, NEEM, ONTOLOGY_OPTIONS, STORE, add_options, moment_from

from oracle.commands.target import connect
from oracle.errors import NeemOracleError

if TYPE_CHECKING:
    from oracle.ontology import OdbOntology


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    top = subparsers.add_parser(
        "prolog", help="SWI-Prolog toplevel with the NEEM store connected (piped queries: every answer)",
        description="Interactive toplevel on a terminal. Queries piped in are answered one by one with every "
        "answer (or --answers N), and the exit status is 1 when one raised an error. -g GOAL runs goals as "
        "'swipl -g GOAL -t halt' does (status 1: a goal failed, 2: it raised an error).")
    top.add_argument("-g", dest="goals", action="append", metavar="GOAL", help="run GOAL once, then exit (repeatable)")
    top.add_argument("-q", "--quiet", action="store_true", help="no banner")
    top.add_argument("--answers", type=int, metavar="N", help="piped queries: print at most N answers each")
    top.add_argument("--create", action="store_true",
                     help="start a new, empty NEEM named --neem (holding the ontology's TBox) and work on it, "
                     "as neem-interface's mem_episode_start expects (the store is made if missing)")
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
    if args.answers is not None and args.answers < 1:
        raise NeemOracleError("--answers must be at least 1")
    if args.json:
        raise NeemOracleError("prolog --json: the toplevel prints answers as Prolog writes them; for JSON use "
                              "why-not, what-next or something-else --json, or json_write_dict/2 in the goal")
    if args.create:
        _create(args)
    bridge, _ = connect(args, write=True)  # a query typed at the toplevel may assert facts
    interactive = not args.goals and sys.stdin.isatty()
    if not args.quiet:
        banner = f"% NEEM {bridge.neem_id} of {bridge.store.location}; KnowRob predicates loaded"
        print(banner + " (halt. or EOF to leave)" if interactive else banner, file=sys.stdout if interactive else sys.stderr)
    sys.stdout.flush()  # Prolog writes to the same file descriptor
    if args.goals:
        for goal in args.goals:
            status = bridge.run_goal(goal)
            if status:
                return status
        return 0
    if not interactive:
        return bridge.run_batch(args.answers)
    bridge.query("prolog")
    return 0


def _create(args: argparse.Namespace) -> None:
    """A new NEEM ``--neem`` for a Prolog session to log into (a name in use is an error)."""
    from oracle.commands.common import ontology_from
    from oracle.neem.writer import NeemLogger
    from oracle.store import open_store

    if args.neem is None:
        raise NeemOracleError("--create needs --neem NAME, the new NEEM's name")
    onto = ontology_from(args)
    with open_store(args.store) as store:
        NeemLogger.create(store, onto, user=args.neem, neem_id=args.neem).close()


def run_why_not(args: argparse.Namespace) -> int:
    from oracle.answers import why_not_sentence
    from oracle.timeline import has_clock

    bridge, onto = connect(args)
    task, objs = _parse_task(args.task, onto)
    at = moment_from(args.at)
    answer = bridge.why_not(task, objs, None if at is None else at.seconds)
    clocked = has_clock(bridge.store.neem(bridge.neem_id).meta)
    print(json.dumps(answer, indent=2) if args.json else why_not_sentence(answer, clocked))
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
