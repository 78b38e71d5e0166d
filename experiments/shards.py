"""Replay one set in shards of users and merge them into the JSON summary `python -m oracle evaluate
CHAINS --baselines --also stacked --json OUT` writes (a 2-core machine shared with other jobs:
the shards run side by side). Each user is replayed from an empty history and its candidates are
shuffled by user and position, so the merged outcomes, in the set's user order, are those of one
run, and so are the summary, the paired intervals and the cold start.

usage: python experiments/shards.py run CHAINS [--odb DIR --mapping YAML] --users A:B --out SHARD.json
           [--also stacked[,NAME]] [--without NAME[,NAME]]
       python experiments/shards.py merge SHARD.json ... --json OUT [--against NAME]
(``--also``: the registry's predictors replayed beside the default, ``stacked`` unless given; ``--without``:
baselines left out, e.g. ``gbdt`` where its figures of an earlier run are cited instead.)
"""

from __future__ import annotations

import argparse
import json
import dataclasses
import sys
from collections import OrderedDict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from oracle.algorithm.params import Hyperparameters  # noqa: E402
from oracle.evaluation.replay import (OracleMethod, Outcome, ReplayResult, ReplayRules, load_users, make_methods,  # noqa: E402
                                      replay, summarize)
from oracle.evaluation.statistics import cold_start_summary, comparison_summary  # noqa: E402
from oracle.ontology import build_ontology  # noqa: E402


def run(args: argparse.Namespace) -> None:
    ontology = build_ontology(args.odb, args.mapping)
    users = load_users(args.chains)
    first, _, last = args.users.partition(":")
    chosen = OrderedDict(list(users.items())[int(first):int(last) if last else None])
    left_out = {name for name in args.without.split(",") if name}
    methods = [m for m in make_methods(ontology, Hyperparameters(), True) if m.name not in left_out]
    for at, name in enumerate((n for n in args.also.split(",") if n), start=1):
        methods.insert(at, OracleMethod(ontology, Hyperparameters(), method=name, served=True))
    result = replay(ontology, chosen, methods, 0, None, ReplayRules())
    # plain JSON, never a pickle: a shard is a file merge reads back
    Path(args.out).write_text(json.dumps([dataclasses.asdict(o) for o in result.outcomes]) + "\n", encoding="utf-8")


def merge(args: argparse.Namespace) -> None:
    outcomes = [Outcome(**o) for path in args.shards for o in json.loads(Path(path).read_text(encoding="utf-8"))]
    result = ReplayResult(outcomes)
    summary = summarize(result)
    names = result.methods()
    summary["method"] = names[0]
    summary["comparisons"] = comparison_summary(outcomes, names[0], names[1:], 0)
    summary["cold_start"] = cold_start_summary(result, 0)
    summary["protocol"] = {"candidates": "history", "decision": "previous-end", "served": True}
    summary["shards"] = [str(p) for p in args.shards]
    if args.against:  # one more method's paired differences against every other one (e.g. online)
        summary["against"] = comparison_summary(outcomes, args.against, [n for n in names if n != args.against], 0)
    Path(args.json).write_text(json.dumps(summary, indent=1) + "\n", encoding="utf-8")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    one = sub.add_parser("run")
    one.add_argument("chains")
    one.add_argument("--odb")
    one.add_argument("--mapping")
    one.add_argument("--users", required=True)
    one.add_argument("--out", required=True)
    one.add_argument("--also", default="stacked")
    one.add_argument("--without", default="")
    many = sub.add_parser("merge")
    many.add_argument("shards", nargs="+")
    many.add_argument("--json", required=True)
    many.add_argument("--against", default="", help="also pair this method against every other one")
    args = parser.parse_args()
    run(args) if args.command == "run" else merge(args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
