"""What `rank` offers the history steps of a NEEM without imagined situations, replayed.

usage: python scripts/offer-trial.py CHAINS [--odb DIR --mapping YAML]
The replay offers a row without an ``available`` set every distinct action of the user in the
input (the decision's candidates) and the routine predictor learns each step with that offer.
`rank` reads a NEEM's history instead, where such an action has no imagined situation. This
replays the default routine predictor three times, with the same candidates at every decision,
and changes only what each learned step is offered: "replay" (the candidates, as the replay
does), "nothing" (`rank` before 2026-12-04) and "done before" (the distinct actions the user did
before the step, first done first: `oracle.calls.steps_from_history` since). Prints Top-1/3/5.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
from collections.abc import Sequence
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from oracle.algorithm.records import Option, Step  # noqa: E402
from oracle.algorithm.routine import RoutineOracle  # noqa: E402
from oracle.calls import DoneBefore, opening_tasks  # noqa: E402
from oracle.evaluation.replay import KS, load_users, replay  # noqa: E402
from oracle.ontology import OdbOntology, build_ontology  # noqa: E402

MODES = ("replay", "nothing", "done before")


class Offered:
    """The default routine predictor; each learned step is offered as ``mode`` says."""

    def __init__(self, ontology: OdbOntology, mode: str) -> None:
        self.name = self.mode = mode
        self.distances, self.opening = ontology.distances(), opening_tasks(ontology)
        self.reset()

    def reset(self) -> None:
        self.model = RoutineOracle(self.distances, opening_tasks=self.opening).fit([])
        self.done = DoneBefore()

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None, at: float | None = None) -> list[Option]:
        return list(self.model.rank(list(candidates), time_of_day, tree_roots=0, at=at).options())

    def observe(self, step: Step) -> None:
        if not step.idle:
            if self.mode == "nothing":
                step = dataclasses.replace(step, options=())
            elif self.mode == "done before":
                step = dataclasses.replace(step, options=self.done.offer())
            self.done.add(Option(step.task, step.target, step.reference))
        self.model.partial_fit(step)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("chains", type=Path)
    parser.add_argument("--odb", type=Path)
    parser.add_argument("--mapping", type=Path)
    args = parser.parse_args()
    ontology = build_ontology(args.odb, args.mapping)
    users = load_users(args.chains)
    if any(row.available is not None for rows in users.values() for row in rows):
        parser.error(f"{args.chains}: rows carry available sets; this trial is for chains without them")
    methods = [Offered(ontology, mode) for mode in MODES]
    outcomes = replay(ontology, users, methods).outcomes
    print(f"{args.chains}: {len(outcomes)} predictions")
    print("| offer of a learned step | " + " | ".join(f"Top-{k}" for k in KS) + " |")
    print("| --- |" + " ---: |" * len(KS))
    for mode in MODES:
        hits = [sum(1 for o in outcomes if (o.ranks[mode] or k + 1) <= k) / len(outcomes) for k in KS]
        print(f"| {mode} | " + " | ".join(f"{h:.4f}" for h in hits) + " |")


if __name__ == "__main__":
    main()
