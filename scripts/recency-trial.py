"""A trial of the eighth round (docs/algorithm.md): the routine predictor with one more lift, by
how long ago the user last did each offered option, replayed beside the default.

usage: python scripts/recency-trial.py CHAINS [--odb DIR --mapping YAML]
       [--level post|top|base] [--odds offer|model] [--edges S,S,...]

Each offered option falls in one bucket of the time since the user last did it (``--edges``, in
seconds: the default 1 min, 10 min, 1 h, 4 h, 12 h, 36 h make seven, and "never done" is the
eighth). Bucket ``b`` weighs ``(h_b + 1) / (s_b + 1)``: ``h_b`` counts this user's past decisions
whose option done was in ``b``; ``s_b`` sums the share of each decision's offer in ``b``
(``--odds offer``), or the probability the predictor gave those options (``--odds model``, with
``--level post`` only). Only decisions whose offer spans two buckets or more count or are
reweighted; rows without a clock change nothing. ``--level`` places the weights on the leading
variant's final distribution, outside the model (``post``), on each variant's blend where the
self-tuning scores them (``top``), or on ``Q`` with the objects in hand's (``base``).

A trial, not an option of the predictor: it reaches into the fitted model (its ``hand_`` and
``fresh_`` lifts carry the extra weights), so it is tied to this code's ``routine.py``. It prints
Top-1/3/5 of the default and the difference of the trial in points.
"""

from __future__ import annotations

import argparse
import bisect
import importlib.util
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from oracle.algorithm.focus import FeatureLift, combined  # noqa: E402
from oracle.algorithm.records import Option, Step  # noqa: E402
from oracle.evaluation.replay import load_users, replay  # noqa: E402
from oracle.ontology import build_ontology  # noqa: E402
from oracle.timeline import seconds_of  # noqa: E402

_spec = importlib.util.spec_from_file_location("routine_variants", Path(__file__).with_name("routine-variants.py"))
assert _spec is not None and _spec.loader is not None
_variants = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_variants)

EDGES = (60.0, 600.0, 3600.0, 4 * 3600.0, 12 * 3600.0, 36 * 3600.0)


def key(option: Option | Step) -> tuple[str, str | None, str | None]:
    return option.task, option.target, option.reference


@dataclass
class Extra(FeatureLift):
    """A lift that also multiplies in the trial's weights of the decision at hand."""

    extra: np.ndarray | None = None

    def weights(self, inside: np.ndarray | None, odds: bool) -> np.ndarray | None:
        return combined(super().weights(inside, odds), self.extra)


class Recency(_variants.Routine):  # type: ignore[name-defined]
    """The default routine predictor with the recency lift, behind the replay's Method interface."""

    def __init__(self, ontology: Any, name: str, users: list[list[Any]], level: str, odds: str,
                 edges: Sequence[float], gate: float | None = None) -> None:
        self.users, self.level, self.odds, self.edges, self.gate = users, level, odds, tuple(edges), gate
        self.user = -2  # the constructor resets once, then the replay once per user
        super().__init__(ontology, name, {})

    def reset(self) -> None:
        super().reset()
        self.user += 1
        self.row = 0
        self.last: dict[tuple[str, str | None, str | None], float] = {}
        self.hits = [0.0] * (len(self.edges) + 2)
        self.share = [0.0] * (len(self.edges) + 2)
        self.pending: tuple[list[Option], list[int], list[float]] | None = None
        self.orders: tuple[list[Option], list[Option]] | None = None  # plain, lifted (post)
        self.lead = 0.0     # the gate's sum of Top-1 hit differences, lifted minus plain
        self.spread = 0.0   # ... and of their squares
        for holder, attr in ((self.model, "hand_"), (self.model.fresh_, "lift")):
            lift = getattr(holder, attr)
            setattr(holder, attr, Extra(lift.hits, lift.share, lift.steps))

    def _now(self) -> float | None:
        rows = self.users[self.user] if 0 <= self.user < len(self.users) else []
        row = rows[self.row] if self.row < len(rows) else None
        return seconds_of(row.time) if row is not None and row.time is not None else None

    def _set(self, weights: np.ndarray | None) -> None:
        if self.level == "base":
            self.model.hand_.extra = weights
        elif self.level == "top":
            self.model.fresh_.lift.extra = weights

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None, at: float | None = None) -> list[Option]:
        offered = list(candidates)
        now = self._now()
        buckets = [len(self.edges) + 1 if (t := self.last.get(key(o))) is None
                   else bisect.bisect_right(self.edges, now - t) for o in offered] if now is not None else []
        spans = len(set(buckets)) >= 2
        weights = np.array([(self.hits[b] + 1) / (self.share[b] + 1) for b in buckets]) if spans else None
        self._set(weights)
        ranking = self.model.rank(offered, time_of_day, tree_roots=0)
        probability = {key(t.option): t.probability for t in ranking}
        self.pending = (offered, buckets, [probability[key(o)] for o in offered]) if spans else None
        self.orders = None
        if self.level != "post" or weights is None:
            return list(ranking.options())
        final = [probability[key(o)] * w for o, w in zip(offered, weights)]
        order = sorted(range(len(offered)), key=lambda i: (-final[i], i))
        lifted = [offered[i] for i in order]
        self.orders = (list(ranking.options()), lifted)
        if self.gate is not None and not self.lead > self.gate * self.spread ** 0.5:
            return self.orders[0]
        return lifted

    def observe(self, step: Step) -> None:
        self.model.partial_fit(step)  # scored with this decision's weights still set
        self._set(None)
        if step.idle:
            return
        if self.pending is not None:
            offered, buckets, probability = self.pending
            truth = next(i for i, o in enumerate(offered) if key(o) == key(step))
            self.hits[buckets[truth]] += 1
            if self.orders is not None:
                plain, lifted = self.orders
                d = float(key(lifted[0]) == key(step)) - float(key(plain[0]) == key(step))
                self.lead += d
                self.spread += d * d
            for b, p in zip(buckets, probability):
                self.share[b] += p if self.odds == "model" else 1 / len(offered)
        if (now := self._now()) is not None:
            self.last[key(step)] = now
        self.row += 1
        self.pending = None


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("chains")
    parser.add_argument("--odb")
    parser.add_argument("--mapping")
    parser.add_argument("--level", choices=("post", "top", "base"), default="top")
    parser.add_argument("--odds", choices=("offer", "model"), default="offer")
    parser.add_argument("--edges", default=",".join(f"{e:g}" for e in EDGES))
    parser.add_argument("--gate", type=float, default=None,
                        help="with --level post: use the lift for a user only once its Top-1 hits lead the plain"
                             " ranking's by this many standard errors of the paired differences (the switch margin)")
    args = parser.parse_args()
    if args.gate is not None and args.level != "post":
        parser.error("--gate needs --level post")
    if args.odds == "model" and args.level != "post":
        parser.error("--odds model needs --level post (the model's probabilities before the lift)")
    try:
        edges = sorted(float(e) for e in args.edges.split(","))
    except ValueError:
        parser.error(f"--edges {args.edges}: not seconds separated by commas")
    ontology = build_ontology(args.odb, args.mapping, None)
    users = load_users(args.chains)
    methods = [_variants.Routine(ontology, "routine", {}),
               Recency(ontology, "recency", list(users.values()), args.level, args.odds, edges, args.gate)]
    result = replay(ontology, users, methods, 0)
    n = len(result.outcomes)

    def hits(name: str, k: int) -> int:
        ranks = [o.ranks[name] for o in result.outcomes]
        return sum(1 for r in ranks if r is not None and r <= k)

    base = [hits("routine", k) for k in (1, 3, 5)]
    print(f"{args.chains}: {n} predictions; routine " + " / ".join(f"{b / n:.3f}" for b in base))
    gated = "" if args.gate is None else f", gate z {args.gate:g} on Top-1"
    print(f"recency ({args.level}, {args.odds} odds, edges {','.join(f'{e:g}' for e in edges)}{gated}), points: "
          + " / ".join(f"{100 * (hits('recency', k) - b) / n:+.2f}" for k, b in zip((1, 3, 5), base)))


if __name__ == "__main__":
    main()
