"""A NEEM's own history replayed as ``evaluate`` replays a chains file (the explorer's decisions
and its rolling Top-k curve): the history rows become chain rows, ``replay`` ranks each decision,
and a recording wrapper keeps the order the predictor gave, not only the truth's rank.

``neem_chains`` is the same rows as a chains file, so ``python -m oracle evaluate`` on it gives
the figures the explorer shows (tests/service/test_explore.py holds them equal).

With a shared prior (``serve --prior``, or the store's own), the personal predictor blends the
others' habits into each score; the recording wrapper then also notes, per decision, the prior's
share of the ranking (``personal.prior_share``) from the very rows and weights the predictor
scored the offer with: it wraps the replay's own model's ``_combined``, the one place that holds
both, and hands back its result unchanged (no ranking differs; a test holds both equal).
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from oracle.algorithm.params import Hyperparameters
from oracle.algorithm.personal import PersonalOracle, prior_share
from oracle.algorithm.prior import Prior
from oracle.algorithm.records import Option, Step
from oracle.bridge.records import HistoryRow
from oracle.calls import option_of
from oracle.chains import ChainRow, parse_call
from oracle.evaluation.replay import KS, Method, ReplayRules, make_methods, replay, summarize
from oracle.ontology import OdbOntology
from oracle.timeline import clock

#: The history's call of an odb:IdleTask action; replay inserts idle steps from the gaps itself.
IDLE_CALL = "idle"


@dataclass(frozen=True)
class Decision:
    """One replayed decision: when it was ranked, what the user did, the predictor's order
    (at most ``keep`` calls) and the truth's rank in it (None: it was not among the candidates)."""

    index: int
    begin: float
    truth: str
    ranked: tuple[str, ...]
    rank: int | None
    candidates: int
    #: the shared prior's share of the ranking (0..1), None where it took no part (no prior,
    #: or the routine predictor ranked alone)
    prior_share: float | None = None


@dataclass(frozen=True)
class NeemReplay:
    decisions: tuple[Decision, ...]
    #: ``summarize``'s JSON, as ``evaluate --json`` writes it.
    summary: dict[str, Any]
    method: str
    #: whether the predictor was given a shared prior
    prior: bool = False

    def rolling(self, window: int) -> dict[str, list[float]]:
        """Top-k over the last ``window`` decisions at each decision (fewer at the start)."""
        out: dict[str, list[float]] = {}
        for k in KS:
            hits = [1 if d.rank is not None and d.rank <= k else 0 for d in self.decisions]
            total, curve = 0, []
            for i, hit in enumerate(hits):
                total += hit - (hits[i - window] if i >= window else 0)
                curve.append(total / min(i + 1, window))
            out[f"top{k}"] = curve
        return out


def neem_chains(rows: Sequence[HistoryRow], user: str) -> list[ChainRow]:
    """The executed actions of a NEEM as chain rows (idle actions left out: replay puts them back
    from the gaps), with their times and the situation each was chosen in."""
    out: list[ChainRow] = []
    for row in rows:
        if row["call"] == IDLE_CALL:
            continue
        available = tuple(parse_call(c) for c in row["available"]) if row["available"] is not None else None
        out.append(ChainRow(user, parse_call(row["call"]), clock(row["begin"]), available, end=clock(row["end"])))
    return out


class _Recording:
    """A method that notes the order it ranked each decision in (the replay keeps only ranks) and,
    for the personal predictor, the shared prior's share of that ranking (module docstring)."""

    def __init__(self, inner: Method, keep: int) -> None:
        self.inner = inner
        self.name = inner.name
        self.keep = keep
        self.orders: list[tuple[Option, ...]] = []
        self.shares: list[float | None] = []
        self._seen: list[float | None] = []

    def use_prior(self, prior: Any) -> None:
        use = getattr(self.inner, "use_prior", None)
        if use is not None:
            use(prior)

    def reset(self) -> None:
        self.inner.reset()
        model = getattr(self.inner, "model", None)
        if isinstance(model, PersonalOracle):
            combined = model._combined  # the class's, bound: the wrapper only looks at its arguments

            def seen(log_p: np.ndarray, x: np.ndarray, w: np.ndarray) -> np.ndarray:
                given = model.prior is not None  # without one its columns are 0: it took no part
                self._seen.append(prior_share(log_p, x, w, model.served_weight() or 0.0) if given else None)
                return combined(log_p, x, w)

            model._combined = seen  # type: ignore[method-assign]

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None, at: float | None = None) -> list[Option]:
        self._seen.clear()
        order = self.inner.rank(candidates, time_of_day, at)
        self.orders.append(tuple(order[: self.keep]))
        self.shares.append(self._seen[-1] if self._seen else None)
        return order

    def observe(self, step: Step) -> None:
        self.inner.observe(step)


def replay_neem(ontology: OdbOntology, settings: Hyperparameters, method: str, rows: Sequence[HistoryRow],
                user: str, keep: int = 10, prior: Prior | None = None) -> NeemReplay:
    """Replay the NEEM's history with ``method`` under evaluate's default rules (``prior``: the
    shared prior the predictor ranks with, as the service's sessions do)."""
    chains = neem_chains(rows, user)
    rules = ReplayRules()
    recording = _Recording(make_methods(ontology, settings, False, method, rules.served)[0], keep)
    result = replay(ontology, OrderedDict([(user, chains)]), [recording], protocol=rules,
                    priors=None if prior is None else lambda _: prior)
    said: dict[Option, str] = {}
    for row in chains:
        for call in (row.action, *(row.available or ())):
            said.setdefault(option_of(ontology, call), str(call))
    decisions: list[Decision] = []
    orders, shares = iter(recording.orders), iter(recording.shares)
    for outcome, row in zip(result.outcomes, chains):
        order, share = (next(orders), next(shares)) if outcome.n_candidates else ((), None)
        decisions.append(Decision(outcome.index, row.time.timestamp() if row.time else 0.0, str(row.action),
                                  tuple(said.get(o, str(o)) for o in order), outcome.ranks[recording.name], outcome.n_candidates,
                                  share))
    return NeemReplay(tuple(decisions), summarize(result), recording.name, prior is not None)


__all__ = ["Decision", "NeemReplay", "neem_chains", "replay_neem"]
