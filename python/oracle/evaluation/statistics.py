"""Paired comparisons of methods replayed on the same predictions.

Every method ranks the same candidates at the same steps, so methods are compared pairwise on the
same units (users, or blocks of one user's predictions when a data set has few users):
- the difference of pooled Top-k accuracy (method minus reference), with a 95 % percentile
  bootstrap interval that resamples whole units with replacement (seeded);
- a two-sided Wilcoxon signed-rank test on the per-unit accuracy differences;
- Holm's step-down correction over the family of comparisons against one reference, per k.
Choices and their reasons: docs/evaluation.md, "Statistics".
"""

from __future__ import annotations

from typing import Any

from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.stats import wilcoxon

from oracle.evaluation.replay import KS, Outcome, ReplayResult, summarize

#: With fewer users than this, one user's predictions are cut into blocks that are resampled instead.
MIN_USERS = 10
#: Consecutive predictions of one user that form one resampling unit on a data set with few users.
BLOCK = 50
RESAMPLES = 10_000
LEVEL = 0.95
#: Cold start: the first this many predictions of every user, where a method has the least history.
COLD_START = 30


@dataclass(frozen=True)
class Units:
    """Predictions grouped into resampling units: their sizes and each method's hits per unit at k."""

    kind: str
    labels: tuple[str, ...]
    sizes: np.ndarray
    hits: dict[tuple[str, int], np.ndarray]


@dataclass(frozen=True)
class Comparison:
    method: str
    reference: str
    k: int
    difference: float
    low: float
    high: float
    p: float
    p_holm: float

    def to_dict(self) -> dict[str, Any]:
        return {"difference": self.difference, "low": self.low, "high": self.high, "p": self.p, "p_holm": self.p_holm}


def units_of(outcomes: Sequence[Outcome], methods: Sequence[str], ks: Sequence[int] = KS) -> Units:
    """Users as units, or blocks of ``BLOCK`` consecutive predictions of a user when there are few users."""
    users = list(OrderedDict.fromkeys(o.user for o in outcomes))
    by_user = len(users) >= MIN_USERS
    index: dict[str, int] = {}
    unit_of: list[int] = []
    for o in outcomes:
        label = o.user if by_user else f"{o.user}#{o.index // BLOCK}"
        unit_of.append(index.setdefault(label, len(index)))
    units = np.asarray(unit_of, dtype=np.int64)
    sizes = np.bincount(units, minlength=len(index)).astype(float)
    hits: dict[tuple[str, int], np.ndarray] = {}
    for name in methods:
        ranks = np.asarray([o.ranks[name] if o.ranks[name] is not None else 0 for o in outcomes], dtype=np.int64)
        for k in ks:
            hit = ((ranks >= 1) & (ranks <= k)).astype(float)
            hits[(name, k)] = np.bincount(units, weights=hit, minlength=len(index))
    kind = "user" if by_user else f"block of {BLOCK} consecutive predictions of a user"
    return Units(kind, tuple(index), sizes, hits)


def bootstrap_interval(diff_hits: np.ndarray, sizes: np.ndarray, seed: int,
                       resamples: int = RESAMPLES, level: float = LEVEL) -> tuple[float, float]:
    """Percentile interval of sum(diff_hits) / sum(sizes) over units drawn with replacement."""
    count = len(sizes)
    if count == 0:
        return (0.0, 0.0)
    rng = np.random.default_rng(seed)
    draws = rng.integers(0, count, size=(resamples, count))
    values = diff_hits[draws].sum(axis=1) / sizes[draws].sum(axis=1)
    tail = 100 * (1 - level) / 2
    low, high = np.percentile(values, [tail, 100 - tail])
    return (float(low), float(high))


def wilcoxon_p(differences: np.ndarray) -> float:
    """Two-sided Wilcoxon signed-rank p of paired per-unit differences (zeros dropped); 1 if all are zero."""
    nonzero = differences[differences != 0]
    if len(nonzero) == 0:
        return 1.0
    return float(wilcoxon(nonzero, alternative="two-sided").pvalue)


def holm(pvalues: Sequence[float]) -> list[float]:
    """Holm's step-down adjusted p-values (family-wise error), in the input order."""
    m = len(pvalues)
    order = sorted(range(m), key=lambda i: pvalues[i])
    adjusted = [0.0] * m
    running = 0.0
    for rank, i in enumerate(order):
        running = max(running, min(1.0, (m - rank) * pvalues[i]))
        adjusted[i] = running
    return adjusted


def compare(outcomes: Sequence[Outcome], reference: str, others: Sequence[str], seed: int = 0,
            ks: Sequence[int] = KS) -> tuple[Units, list[Comparison]]:
    """Every method in ``others`` against ``reference``: difference, interval, p and Holm-adjusted p per k."""
    units = units_of(outcomes, [reference, *others], ks)
    found: list[Comparison] = []
    for k in ks:
        rows = []
        for position, name in enumerate(others):
            diff = units.hits[(name, k)] - units.hits[(reference, k)]
            total = units.sizes.sum()
            low, high = bootstrap_interval(diff, units.sizes, seed + 7919 * k + position)
            per_unit = diff / np.maximum(units.sizes, 1)
            rows.append((name, float(diff.sum() / total) if total else 0.0, low, high, wilcoxon_p(per_unit)))
        adjusted = holm([row[4] for row in rows])
        found.extend(Comparison(name, reference, k, d, lo, hi, p, q)
                     for (name, d, lo, hi, p), q in zip(rows, adjusted))
    return units, found


def comparison_summary(outcomes: Sequence[Outcome], reference: str, others: Sequence[str], seed: int = 0) -> dict[str, Any]:
    """The JSON block of ``compare``: per method, per k, the paired difference against the reference."""
    units, found = compare(outcomes, reference, others, seed)
    methods: dict[str, dict[str, Any]] = {name: {} for name in others}
    for c in found:
        methods[c.method][f"top{c.k}"] = c.to_dict()
    return {"reference": reference, "unit": units.kind, "units": len(units.labels), "resamples": RESAMPLES,
            "level": LEVEL, "seed": seed, "test": "Wilcoxon signed-rank, two-sided, Holm-corrected per k",
            "methods": methods}


def cold_start_summary(result: ReplayResult, seed: int = 0, first: int = COLD_START) -> dict[str, Any]:
    """Top-k of every method over each user's first ``first`` predictions, paired against the first method."""
    early = [o for o in result.outcomes if o.index < first]
    methods = result.methods()
    summary = summarize(ReplayResult(early))
    out: dict[str, Any] = {"first_predictions": first, "n_predictions": len(early),
                 "methods": {m: {f"top{k}": summary["methods"][m][f"top{k}"] for k in KS} for m in methods},
                 "chance": summary["chance"]}
    if len(methods) > 1 and early:
        out["comparisons"] = comparison_summary(early, methods[0], methods[1:], seed)
    return out


__all__ = ["BLOCK", "COLD_START", "LEVEL", "MIN_USERS", "RESAMPLES", "Comparison", "Units", "bootstrap_interval",
           "cold_start_summary", "compare", "comparison_summary", "holm", "units_of", "wilcoxon_p"]
