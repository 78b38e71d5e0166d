"""Replay a chains file with routine predictors of other constructor parameters, beside the n-gram.

usage: python experiments/routine-variants.py CHAINS [--odb DIR --mapping YAML] [--baselines A,B|all]
       [--alternatives first|conditions] [NAME=JSON ...]
Each NAME=JSON builds ``RoutineOracle(distances, **JSON)`` (e.g. 'fixed={"tuning": "fixed"}');
without any, a fixed set of alternatives to the defaults is replayed (``--alternatives``: the
first round's, or those tried on the condition-matched sets). ``--baselines all`` replays every
baseline and adds a row with the best of them per k. Prints Top-1/3/5 per
predictor and Top-1/Top-3 per kind of step: the exact 3-token context was already followed by
the truth ("exact"), the action was done before but not after that context ("known"), the user's
first use of the action ("first"), right after an idle gap ("after idle"). Development runs use
the persona tuning split, never a test split (docs/algorithm.md, "What did not help").
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import Counter
from collections.abc import Sequence
from typing import Any
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from oracle.algorithm.records import Option, Step  # noqa: E402
from oracle.algorithm.routine import RoutineOracle  # noqa: E402
from oracle.calls import opening_tasks  # noqa: E402
from oracle.errors import NeemOracleError  # noqa: E402
from oracle.evaluation.baselines import BASELINES  # noqa: E402
from oracle.evaluation.replay import load_users, replay  # noqa: E402
from oracle.ontology import OdbOntology, build_ontology  # noqa: E402

#: the first round, against the default of that round (no novelty variants: pinned off in every row)
FIRST_ROUND: dict[str, dict[str, Any]] = {
    "default": {},
    "before: untimed, margin 0": {"timed": [False], "switch_margin": 0.0},
    "untimed": {"timed": [False]},
    "margin 0": {"switch_margin": 0.0},
    "margin 1": {"switch_margin": 1.0},
    "timed from order 1": {"timed_from": 1},
    "timed + untimed variants": {"timed": [True, False]},
    "discount variants": {"discounts": [False, True]},
    "orders 3,5,2,1": {"orders": [3, 5, 2, 1]},
    "temperatures 0.25,2": {"temperatures": [0.25, 2.0]},
    "context_decay 0.3": {"context_decay": 0.3},
    "time_of_day_penalty 1": {"time_of_day_penalty": 1.0},
    "fixed": {"tuning": "fixed"},
    "mixture": {"tuning": "mixture"},
}
ALTERNATIVES: dict[str, dict[str, Any]] = {name: {"novelty": [False], **params} for name, params in FIRST_ROUND.items()}

#: tried on the nine development sets with the condition-matched ones (docs/algorithm.md); the
#: first row is the default before them, each row names its parameters in full against today's defaults
CONDITIONS: dict[str, dict[str, Any]] = {
    "before: no novelty variants": {"novelty": [False]},
    "default: novelty variants": {},
    "novelty only": {"novelty": [True]},
    "novelty variants, margin 1": {"switch_margin": 1.0},
    "novelty variants + timed gate z 1.645": {"timed_gate": 1.645},
    "timed gate z 1.645": {"novelty": [False], "timed_gate": 1.645},
    "timed gate z 0": {"novelty": [False], "timed_gate": 0.0},
    "exclusion": {"novelty": [False], "exclusion": True},
    "timed gate z 1.645 + exclusion": {"novelty": [False], "timed_gate": 1.645, "exclusion": True},
    "timed + untimed variants": {"novelty": [False], "timed": [True, False]},
    "orders 3,5,2": {"novelty": [False], "orders": [3, 5, 2]},
    "discount variants": {"novelty": [False], "discounts": [False, True]},
}
ROUNDS: dict[str, dict[str, dict[str, Any]]] = {"first": ALTERNATIVES, "conditions": CONDITIONS}


class Routine:
    """A RoutineOracle of given parameters behind the replay's Method interface."""

    def __init__(self, ontology: OdbOntology, name: str, params: dict[str, Any]) -> None:
        self.name, self.params = name, params
        self.distances, self.opening = ontology.distances(), opening_tasks(ontology)
        self.reset()

    def reset(self) -> None:
        params: dict[str, Any] = {k: tuple(v) if isinstance(v, list) else v for k, v in self.params.items()}
        self.model = RoutineOracle(self.distances, opening_tasks=self.opening, **params).fit([])

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None, at: float | None = None) -> list[Option]:
        return list(self.model.rank(list(candidates), time_of_day, tree_roots=0, at=at).options())

    def observe(self, step: Step) -> None:
        self.model.partial_fit(step)


class Kinds:
    """Ranks nothing; labels each predicted step by what the history knew of its truth."""

    name = "kinds"

    def __init__(self) -> None:
        self.labels: list[set[str]] = []
        self.reset()

    def reset(self) -> None:
        self.tokens: list[object] = []
        self.done: Counter[object] = Counter()
        self.followed: set[tuple] = set()

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None, at: float | None = None) -> list[Option]:
        return list(candidates)

    def observe(self, step: Step) -> None:
        token = "idle" if step.idle else step.option
        context = tuple(self.tokens[-3:])
        if not step.idle:
            kind = "first" if not self.done[token] else "exact" if (context, token) in self.followed else "known"
            self.labels.append({"all", kind} | ({"after idle"} if self.tokens and self.tokens[-1] == "idle" else set()))
            self.done[token] += 1
        if len(context) == 3:
            self.followed.add((context, token))
        self.tokens.append(token)


def _params(parser: argparse.ArgumentParser, name: str, text: str) -> dict[str, Any]:
    """The constructor parameters of ``NAME=JSON`` (a JSON object), or a one-line usage error."""
    try:
        params = json.loads(text)
    except json.JSONDecodeError as error:
        parser.error(f"{name}={text}: not NAME=JSON ({error.msg}); a name holds no '='")
    if not isinstance(params, dict):
        parser.error(f"{name}={text}: the parameters must be a JSON object")
    return params


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("chains")
    parser.add_argument("--odb")
    parser.add_argument("--mapping")
    parser.add_argument("--baselines", default="ngram", help="comma-separated baselines to replay beside, or all")
    parser.add_argument("--alternatives", choices=sorted(ROUNDS), default="first")
    parser.add_argument("variants", nargs="*", metavar="NAME=JSON")
    args = parser.parse_intermixed_args()
    variants = {name: _params(parser, name, text) for name, _, text in (v.partition("=") for v in args.variants)}
    variants = variants or ROUNDS[args.alternatives]
    baselines = list(BASELINES) if args.baselines == "all" else [b.strip() for b in args.baselines.split(",") if b.strip()]
    unknown = [b for b in baselines if b not in BASELINES]
    if unknown:
        parser.error(f"unknown baseline {unknown[0]!r}; known: {', '.join(BASELINES)}")
    ontology = build_ontology(args.odb, args.mapping, None)
    users = load_users(args.chains)
    kinds = Kinds()
    methods = [*(Routine(ontology, name, params) for name, params in variants.items()),
               *(BASELINES[b]() for b in baselines), kinds]
    result = replay(ontology, users, methods, 0)
    names = [m.name for m in methods[:-1]]
    groups = ("all", "exact", "known", "first", "after idle")
    shares = {g: sum(g in labels for labels in kinds.labels) / len(kinds.labels) for g in groups}
    print(f"{args.chains}: {len(users)} users, {len(result.outcomes)} predictions; share of steps: "
          + ", ".join(f"{g} {100 * shares[g]:.1f} %" for g in groups[1:]) + "\n")
    print("| predictor | Top-1 | Top-3 | Top-5 | " + " | ".join(f"{g} Top-1/3" for g in groups[1:]) + " |")
    print("| --- | ---: | ---: | ---: | " + " | ".join("---:" for _ in groups[1:]) + " |")
    def rate(name: str, group: str, k: int) -> float:
        ranks = [o.ranks[name] for o, labels in zip(result.outcomes, kinds.labels) if group in labels]
        return sum(1 for r in ranks if r is not None and r <= k) / max(1, len(ranks))

    for name in names:
        print(f"| {name} | " + " | ".join(f"{rate(name, 'all', k):.3f}" for k in (1, 3, 5)) + " | "
              + " | ".join(f"{rate(name, g, 1):.3f}/{rate(name, g, 3):.3f}" for g in groups[1:]) + " |")
    if args.baselines == "all":
        best = {k: max(baselines, key=lambda b: rate(b, "all", k)) for k in (1, 3, 5)}
        print("| best baseline | " + " | ".join(f"{rate(best[k], 'all', k):.3f} {best[k]}" for k in (1, 3, 5))
              + " |" + " |" * (len(groups) - 1))

    if len(variants) < 2:
        return
    first = names[0]
    print(f"\ndifference to {first!r}, points (100 x fraction):\n")
    print("| predictor | Top-1 | Top-3 | Top-5 |\n| --- | ---: | ---: | ---: |")
    for name in names[1:len(variants)]:
        print(f"| {name} | " + " | ".join(f"{100 * (rate(name, 'all', k) - rate(first, 'all', k)):+.2f}"
                                          for k in (1, 3, 5)) + " |")


if __name__ == "__main__":
    try:
        main()
    except NeemOracleError as error:  # a file that cannot be read, a bad parameter: one line
        sys.exit(f"routine-variants: {error}")
