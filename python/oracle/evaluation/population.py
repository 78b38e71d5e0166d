"""Evaluation that cannot cheat: each user's shared prior from the other users of the file only.

``--population loo`` (leave one user out): every user's chains give their task sequence as a
prior counts it (``sequence_of``: the option's ``task_key``, an ``idle`` token wherever the replay
inserts an idle step); each user's prior is the product's (``prior_counts.Population.without``:
clipped, k users, Laplace noise with ``epsilon``) over every *other* user of the file, built before
the user's replay starts, so no count the predictor ranks with ever saw the user. The noise of each
user's prior is drawn from a generator seeded by the replay's seed and the user.
``--population none``: no prior (the predictors rank as without one).

``pop_ppm`` (a baseline, in ``--baselines``): PPM-C over the others' counts alone (``Prior.probabilities``
after the user's own last three tokens), learning nothing from the user but that context.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable, Sequence

import numpy as np

from oracle.algorithm.prior import DEFAULT_CLIP, DEFAULT_K, IDLE, Prior, option_key
from oracle.algorithm.prior_counts import Population
from oracle.algorithm.records import Option, Step
from oracle.calls import option_of
from oracle.chains import ChainRow
from oracle.evaluation.tokens import order_by_score
from oracle.ontology import OdbOntology
from oracle.timeline import is_idle_gap, seconds_of

POPULATIONS = ("none", "loo")


def sequence_of(ontology: OdbOntology, rows: Sequence[ChainRow]) -> list[str]:
    """A user's tokens as the replay's history has them (idle where a gap of the threshold is)."""
    tokens: list[str] = []
    previous_end: float | None = None
    for row in rows:
        start = seconds_of(row.time) if row.time is not None else None
        if start is not None and is_idle_gap(previous_end, start):
            tokens.append(IDLE)
        if row.time is not None:
            previous_end = seconds_of(row.end if row.end is not None else row.time)
        tokens.append(option_key(option_of(ontology, row.action)))
    return tokens


def leave_one_out(ontology: OdbOntology, users: dict[str, list[ChainRow]], k: int = DEFAULT_K,
                  epsilon: float | None = None, clip: int = DEFAULT_CLIP, seed: int = 0) -> Callable[[str], Prior]:
    """Each user's prior from the other users of ``users`` (module docstring)."""
    population = Population(clip)
    for user, rows in users.items():
        population.add(user, [sequence_of(ontology, rows)])

    def prior(user: str) -> Prior:
        digest = hashlib.sha256(f"prior:{seed}:{user}".encode()).digest()
        return population.without(user, k, epsilon, np.random.default_rng(int.from_bytes(digest[:8], "big")))

    return prior


class PopPPM:
    """``pop_ppm``: the others' counts alone (module docstring)."""

    name = "pop_ppm"

    def __init__(self) -> None:
        self.prior: Prior | None = None
        self.reset()

    def use_prior(self, prior: Prior | None) -> None:
        self.prior = prior

    def reset(self) -> None:
        self.tokens: list[str] = []

    def observe(self, step: Step) -> None:
        self.tokens.append(IDLE if step.idle else option_key(step.option))

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None, at: float | None = None) -> list[Option]:
        if self.prior is None or not candidates:
            return list(candidates)
        probs, _ = self.prior.probabilities(self.tokens[-3:], [option_key(c) for c in candidates])
        return order_by_score(candidates, probs.tolist())


__all__ = ["POPULATIONS", "PopPPM", "leave_one_out", "sequence_of"]
