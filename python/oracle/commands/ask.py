"""``python -m oracle ask "QUESTION"`` and ``summary``: questions about the past and the state
summary of a NEEM (docs/beyond.md)."""

from __future__ import annotations

import argparse
import json

from oracle.commands.common import AT, JSON, NEEM, ONTOLOGY_OPTIONS, STORE, add_options, moment_from

from oracle.commands.target import connect


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    ask = subparsers.add_parser(
        "ask", help="answer a question about the past from the NEEM, in English or German (docs/beyond.md)",
        description="Question forms: when did I last X; how often did I X today / this week; what do I usually "
        "do after X; what did you do this morning / today / this evening; where is the Y; why did you suggest X "
        "(and their German forms). X is a task call, e.g. pick(apple), or in English its words: 'pick the apple'.")
    ask.add_argument("question", help="the question, e.g. 'when did I last open the fridge?'")
    AT.add(ask)
    add_options(ask, STORE, NEEM, JSON, *ONTOLOGY_OPTIONS)
    ask.set_defaults(handler=run_ask)

    summary = subparsers.add_parser("summary", help="the NEEM's state summary as JSON (recent actions, usual next steps)")
    AT.add(summary)
    add_options(summary, STORE, NEEM, *ONTOLOGY_OPTIONS)
    summary.set_defaults(handler=run_summary)


def _seconds(text: str | None) -> float | None:
    moment = moment_from(text)
    return None if moment is None else moment.seconds


def run_ask(args: argparse.Namespace) -> int:
    from oracle.past.ask import ask
    from oracle.timeline import has_clock

    bridge, onto = connect(args)
    clocked = has_clock(bridge.store.neem(bridge.neem_id).meta)
    answer = ask(bridge, onto, args.question, _seconds(args.at), clocked)
    print(json.dumps(answer.to_json(), indent=2, ensure_ascii=False) if args.json else answer.text)
    return 0


def run_summary(args: argparse.Namespace) -> int:
    from oracle.past.summary import state_summary
    from oracle.timeline import has_clock

    bridge, _ = connect(args)
    clocked = has_clock(bridge.store.neem(bridge.neem_id).meta)
    print(json.dumps(state_summary(bridge, _seconds(args.at), clocked), indent=2, ensure_ascii=False))
    return 0
