"""Evaluation data and runs: ``generate`` (persona benchmark) and ``convert`` (real datasets).

Each sub-command parses its arguments and calls one function of ``oracle.world`` or
``oracle.evaluation``; the figures go to stdout, progress to stderr.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

#: Dataset converters by name: module and function (each takes the dataset folder and an out folder).
CONVERTERS = {
    "kasteren": ("oracle.evaluation.convert_kasteren", "convert"),
    "egtea": ("oracle.evaluation.convert_egtea", "convert"),
}


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    generate = subparsers.add_parser(
        "generate",
        help="generate the persona benchmark (chains with available sets, personas.yaml)",
        description="Simulate seeded personas in the kitchen world and write personas.yaml, tune.jsonl "
        "and test.jsonl (17 of 105 personas tune, the rest test; docs/world.md).",
    )
    generate.add_argument("--personas", type=int, default=105, metavar="N", help="number of personas (default 105)")
    generate.add_argument("--days", type=int, default=7, help="simulated days per persona (default 7)")
    generate.add_argument("--seed", type=int, default=0, metavar="K", help="random seed (default 0)")
    generate.add_argument("--world", type=Path, metavar="FILE", help="world file (default ontology/kitchen-world.yaml)")
    generate.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder")
    generate.add_argument("--modes", action="store_true",
                          help="say who performed each action (performed_by: the user or the robot, from the persona's "
                               "autonomy profile; docs/beyond.md, \"Autonomy mode\")")
    generate.set_defaults(handler=run_generate)

    convert = subparsers.add_parser(
        "convert",
        help="convert a real activity dataset into chains, an odb and a mapping",
        description="Turn van Kasteren house A or EGTEA Gaze+ into chains.jsonl, odb/ and mapping.yaml.",
    )
    convert.add_argument("dataset", choices=sorted(CONVERTERS), help="which dataset")
    convert.add_argument("path", type=Path, metavar="PATH", help="the downloaded dataset folder (e.g. datasets/kasteren_house_a)")
    convert.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder")
    convert.set_defaults(handler=run_convert)


def _progress(done: int, total: int) -> None:
    if sys.stderr.isatty() or done == total:
        end = "\n" if done == total else "\r"
        print(f"persona {done}/{total}", end=end, file=sys.stderr, flush=True)


def run_generate(args: argparse.Namespace) -> int:
    from oracle.world.generate import generate
    from oracle.world.worldfile import load_world

    world = load_world(args.world)
    summary = generate(args.out, personas=args.personas, days=args.days, seed=args.seed, world=world, progress=_progress,
                       modes=args.modes)
    print(f"wrote {args.out}/personas.yaml, tune.jsonl ({summary.tune_actions} actions), test.jsonl ({summary.test_actions} actions)")
    print(f"personas {summary.personas}, days {summary.days}, actions {summary.actions}, "
          f"per persona {summary.mean_actions_per_persona:.1f}, available per step {summary.mean_available:.1f}, "
          f"skipped steps {summary.skipped_steps}")
    return 0


def run_convert(args: argparse.Namespace) -> int:
    import importlib

    module_name, function = CONVERTERS[args.dataset]
    convert = getattr(importlib.import_module(module_name), function)
    report = convert(args.path, args.out)
    print(report)
    return 0
