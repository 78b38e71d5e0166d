"""A NEEM's own history replayed as ``evaluate`` replays a chains file (the explorer's decisions
and its rolling Top-k curve): the history rows become chain rows, ``replay`` ranks each decision,
and a recording wrapper keeps the order the predictor gave, not only the truth's rank.

``neem_chains`` is the same rows as a chains file, so ``python -m oracle evaluate`` on it gives
the figures the explorer shows (tests/service/test_explore.py holds them equal).
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from oracle.algorithm.params import Hyperparameters
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


@dataclass(frozen=True)
class NeemReplay:
    decisions: tuple[Decision, ...]
    #: ``summarize``'s JSON, as ``evaluate --json`` writes it.
    summary: dict[str, Any]
    method: str

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
    """A method that notes the order it ranked each decision in (the replay keeps only ranks)."""

    def __init__(self, inner: Method, keep: int) -> None:
        self.inner = inner
        self.name = inner.name
        self.keep = keep
        self.orders: list[tuple[Option, ...]] = []

    def reset(self) -> None:
        self.inner.reset()

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None, at: float | None = None) -> list[Option]:
        order = self.inner.rank(candidates, time_of_day, at)
        self.orders.append(tuple(order[: self.keep]))
        return order

    def observe(self, step: Step) -> None:
        self.inner.observe(step)


def replay_neem(ontology: OdbOntology, settings: Hyperparameters, method: str, rows: Sequence[HistoryRow],
                user: str, keep: int = 10) -> NeemReplay:
    """Replay the NEEM's history with ``method`` under evaluate's default rules."""
    chains = neem_chains(rows, user)
    rules = ReplayRules()
    recording = _Recording(make_methods(ontology, settings, False, method, rules.served)[0], keep)
    result = replay(ontology, OrderedDict([(user, chains)]), [recording], protocol=rules)
    said: dict[Option, str] = {}
    for row in chains:
        for call in (row.action, *(row.available or ())):
            said.setdefault(option_of(ontology, call), str(call))
    decisions: list[Decision] = []
    orders = iter(recording.orders)
    for outcome, row in zip(result.outcomes, chains):
        order = next(orders) if outcome.n_candidates else ()
        decisions.append(Decision(outcome.index, row.time.timestamp() if row.time else 0.0, str(row.action),
                                  tuple(said.get(o, str(o)) for o in order), outcome.ranks[recording.name], outcome.n_candidates))
    return NeemReplay(tuple(decisions), summarize(result), recording.name)


__all__ = ["Decision", "NeemReplay", "neem_chains", "replay_neem"]
