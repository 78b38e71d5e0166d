"""The oracle in the system: history from the NEEM (through Prolog), ranking, write-back.

NEEM -> ``odb_history:situation_history`` (one crossing) -> Steps -> the chosen predictor (its fit
kept between calls, oracle.fitcache) -> ranking -> ``NeemLogger.preference`` (an imagined preference the Prolog answers read).

The answers read the written rank (1 = best) and show the score; for every predictor the score is
lower-is-better: the thesis oracle writes its eq. 4.12 distance, the routine predictor -log2 of its
probability (docs/algorithm.md).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from oracle.algorithm.params import Hyperparameters
from oracle.algorithm.predictors import DEFAULT, make_predictor
from oracle.algorithm.records import RankedTask, Ranking, local_name
from oracle.chains import TaskCall, parse_call
from oracle.errors import LoggingError, NeemOracleError
from oracle.fitcache import FitCache
from oracle.historycache import HistoryCache
from oracle.calls import call_of, check_call, opening_tasks, option_of, steps_before
from oracle.neem.query import recorded_part_of_day
from oracle.neem.writer import NeemLogger
from oracle.ontology import OdbOntology
from oracle.timeline import Instant, has_clock, now, part_of_day_at

if TYPE_CHECKING:
    from oracle.bridge import Bridge

#: Score written for options without similar history (the store and JSON need a finite number).
NO_HISTORY_SCORE = 1e9


@dataclass(frozen=True)
class NeemRanking:
    neem: str
    at: float
    time_of_day: str | None  # None: the NEEM has no clock (oracle.timeline.has_clock)
    history: int
    ranking: Ranking
    calls: tuple[TaskCall, ...]
    chain: tuple[TaskCall, ...]
    milliseconds: float
    written: str | None
    note: str | None
    method: str = DEFAULT


def finite(score: float) -> float:
    return score if math.isfinite(score) else NO_HISTORY_SCORE


def support_fields(task: RankedTask) -> dict[str, Any]:
    """What supports a routine-predictor ranking (empty for the thesis oracle): its probability,
    the exact context it followed (``context_order`` its length; 0: done, not after this context;
    -1: no counted context holds it), the history positions of those past situations (latest
    last, at most 5), the objects in hand it uses (``focus``, local names), whether it is newly
    offered (``new``: not offered at the previous decision) and whether, right after a break, it
    once followed the last action before it (``resumed``) and, where the clock's odds weighed the
    ranking, how many seconds ago the user last did it (``since``)."""
    from oracle.algorithm.records import RoutineTask

    if not isinstance(task, RoutineTask):
        return {}
    return {"probability": task.probability, "context_order": task.order, "context": list(task.context),
            "situations": list(task.situations), "focus": [local_name(obj) for obj in task.focus], "new": task.new,
            "resumed": task.resumed, "since": task.since}


def rank_neem(
    bridge: Bridge,
    ontology: OdbOntology,
    settings: Hyperparameters,
    available: list[str] | None = None,
    at: Instant | None = None,
    *,
    write: bool = True,
    method: str = DEFAULT,
    cache: FitCache | None = None,
    histories: HistoryCache | None = None,
) -> NeemRanking:
    """Rank ``available`` (chain syntax) at ``at`` (default: now), or else the NEEM's latest
    imagined situation, at the part of day recorded with it (oracle.timeline's rule); a NEEM
    that imagined nothing (an import of chains without available sets) gets the actions done so
    far ranked, as ``available``, the offer its history steps get (oracle.calls.steps_from_history).
    In a NEEM without a clock, times are positions with no part of the day, and "now" is the position
    after the last action. The fit is kept in ``cache`` (default: the user's, oracle.fitcache)
    and extended by the actions logged since; so is the history read (``histories``, default:
    the user's, oracle.historycache)."""
    history = (histories or HistoryCache.default()).history(bridge)
    info = bridge.store.neem(bridge.neem_id)
    clocked = has_clock(info.meta)
    latest = None if available else bridge.latest_situation()
    offered = None
    if not available and latest is None:
        before = at.seconds if at is not None else math.inf   # what was done before the decision
        available = list(dict.fromkeys(row["call"] for row in history
                                       if row["call"] != "idle" and float(row["begin"]) < before))
        if not available:
            raise NeemOracleError(f"NEEM {bridge.neem_id!r} has no imagined situation and no action to rank; "
                                  "give the available calls")
        offered = (f"no imagined situation in the NEEM: ranked the {len(available)} actions done so far "
                   "(--available ranks others)")
    if available:
        calls = [parse_call(text) for text in available]
        for call in calls:
            check_call(ontology, call, "available")
        if clocked:
            instant = at if at is not None else now()
        else:
            last = 0.0 if at is not None else max((float(row["end"]) for row in history), default=0.0)
            instant = Instant(at.seconds if at is not None else last, None)
    else:
        assert latest is not None  # no available calls: the NEEM's latest situation, found above
        calls = [parse_call(text) for text in latest["available"]]
        begin = float(latest["begin"])
        recorded = recorded_part_of_day(bridge.store, bridge.neem_id, ontology.vocab, begin)
        instant = Instant(begin, (recorded or part_of_day_at(begin)) if clocked else None)
    when, part = instant.seconds, instant.part_of_day
    steps = steps_before(ontology, history, when, clocked)
    model = make_predictor(method, ontology.distances(), opening_tasks(ontology), settings)
    oracle = (cache or FitCache.default()).fitted(model, steps, bridge.store.location, bridge.neem_id,
                                                  keep=not info.temporary)
    started = time.perf_counter()
    ranking = oracle.rank([option_of(ontology, c) for c in calls], part, at=when if clocked else None)
    elapsed = (time.perf_counter() - started) * 1000
    written = note = None
    if write:
        logger = NeemLogger(bridge.store, ontology, bridge.neem_id)
        try:
            written = logger.preference([(call_of(ontology, t.option), finite(t.score)) for t in ranking], instant)
        except LoggingError as error:
            note = f"ranking not written: {error}"
    if offered is not None:
        note = offered if note is None else f"{offered}; {note}"
    return NeemRanking(bridge.neem_id, when, part, len(steps), ranking,
                       tuple(call_of(ontology, t.option) for t in ranking),
                       tuple(call_of(ontology, o) for o in ranking.chain()), elapsed, written, note, method)
