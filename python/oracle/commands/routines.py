"""``python -m oracle routines``: the user's routines mined from their NEEM, named, stored in it
as workflows, and the one in progress (docs/beyond.md)."""

from __future__ import annotations

import argparse
import json

from oracle.commands.common import AT, JSON, NEEM, ONTOLOGY_OPTIONS, STORE, add_options, moment_from

from oracle.commands.target import connect
from oracle.errors import NeemOracleError


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser(
        "routines", help="the user's recurring chains, with their names, days seen and usual time (docs/beyond.md)",
        description="Mines the NEEM's actions into routines and names each from its steps. --save writes them into the "
        "NEEM as SOMA/DUL workflows (replacing those saved before); --rename KEY NAME gives one a name of the user's, "
        "kept when the routines are mined again.")
    parser.add_argument("--save", action="store_true", help="store the routines in the NEEM as dul:Workflow individuals")
    parser.add_argument("--rename", nargs=2, metavar=("KEY", "NAME"), help="name routine KEY (r1, r2, ...) and save")
    AT.add(parser)
    add_options(parser, STORE, NEEM, JSON, *ONTOLOGY_OPTIONS)
    parser.set_defaults(handler=run)
    register_evaluation(subparsers)


def run(args: argparse.Namespace) -> int:
    from dataclasses import replace

    from oracle.past.mine import NeemRoutines, neem_routines
    from oracle.past.workflows import save_routines

    write = args.save or args.rename is not None
    bridge, onto = connect(args, write=write)
    moment = moment_from(args.at)
    found = neem_routines(bridge, None if moment is None else moment.seconds)
    if args.rename is not None:
        key, name = args.rename[0], " ".join(args.rename[1].split())
        if key not in {r.key for r in found.routines}:
            raise NeemOracleError(f"no routine {key!r}; the routines are {', '.join(r.key for r in found.routines) or 'none'}")
        if not name or len(name) > 200:
            raise NeemOracleError("a routine's name must have 1 to 200 characters")
        routines = tuple(replace(r, name=name) if r.key == key else r for r in found.routines)
        found = NeemRoutines(routines, (*found.named, key), found.current, found.now)
    if write:
        save_routines(bridge.store, onto, bridge.neem_id, found.routines, found.named)
    if args.json:
        print(json.dumps(found.to_json(), indent=2, ensure_ascii=False))
        return 0
    if not found.routines:
        print("no routines yet: no chain recurs on 3 days or more")
    for r in found.routines:
        mark = " (your name)" if r.key in found.named else ""
        print(f"{r.key:>3}  {r.name}{mark}: {r.days} days, usually {r.usual_time} ({r.part}), {len(r.steps)} steps:")
        print("     " + " -> ".join(r.steps))
    if found.current is not None:
        c = found.current
        left = len(c.remaining)
        print(f"in progress: {c.routine.key} {c.routine.name}, {left} step{'s' if left != 1 else ''} left"
              + (f": {' -> '.join(c.remaining)}" if left else ""))
    if write:
        print(f"saved {len(found.routines)} routines in NEEM {bridge.neem_id} as dul:Workflow")
    return 0


def register_evaluation(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    from oracle.commands.common import bounded_int

    parser = subparsers.add_parser(
        "routines-eval", help="score routine mining and recognition against the persona generator's routines",
        description="Per persona of the split: routines mined from all days against its daily routine (precision, "
        "recall); routines mined from the first --train-days, then each later episode of a routine entry "
        "recognised after 1, 2 and 3 steps; and the objects suggested each evening from the fourth day for the next morning, "
        "against the most used objects; and who performs each action (the persona's autonomy profile), predicted "
        "from the earlier actions against the per-task majority.")
    parser.add_argument("--personas", type=bounded_int(1, 10_000), default=105)
    parser.add_argument("--days", type=bounded_int(2, 366), default=7)
    parser.add_argument("--seed", type=bounded_int(0, 1_000_000), default=0)
    parser.add_argument("--train-days", type=bounded_int(1, 365), default=5)
    parser.add_argument("--split", choices=("test", "tune"), default="test")
    add_options(parser, JSON)
    parser.set_defaults(handler=run_evaluation)


def run_evaluation(args: argparse.Namespace) -> int:
    from dataclasses import asdict

    from oracle.evaluation.routines import score_autonomy, score_preparation, score_routines

    if args.train_days >= args.days:
        raise NeemOracleError(f"--train-days ({args.train_days}) must be fewer than --days ({args.days})")
    scores = score_routines(args.personas, args.days, args.seed, args.train_days, args.split)
    prepared = score_preparation(args.personas, args.days, args.seed, split=args.split)
    modes = score_autonomy(args.personas, args.days, args.seed, args.split)
    if args.json:
        print(json.dumps({**asdict(scores), "prepare": asdict(prepared), "autonomy": asdict(modes)}, indent=2))
        return 0
    print(f"{scores.personas} personas ({args.split} split, {args.days} days, seed {args.seed}):")
    print(f"  routines recovered: precision {scores.precision:.3f}, recall {scores.recall:.3f}")
    shown = ", ".join(f"{n} step{'s' if n > 1 else ''} {share:.1%}" for n, share in scores.recognised.items())
    print(f"  in progress recognised (days after {args.train_days}, {scores.runs} runs): {shown}")
    print(f"  episodes of no routine taken for one after 2 steps: {scores.false_alarm_rate:.1%} of {scores.others}")
    print(f"  prepare (the evening before, for the morning; {prepared.nights} nights): used next morning "
          f"{prepared.routines:.1%} of {prepared.suggested} suggested, most-used-objects baseline "
          f"{prepared.baseline:.1%} of {prepared.baseline_suggested}")
    print(f"  autonomy mode ({modes.actions} actions, {modes.robot_share:.1%} by the robot, "
          f"{modes.together_share:.1%} together): predicted right {modes.learned:.1%} (learned), "
          f"{modes.context:.1%} (contexts), per-task majority {modes.task_majority:.1%}, "
          f"the generator's own odds {modes.ceiling:.1%}; right only by the learned predictor {modes.learned_only}, "
          f"only by the baseline {modes.baseline_only}; together said for {modes.together_recall:.1%} of the "
          f"actions done together")
    return 0
