"""The oracle in the system: history from the NEEM (through Prolog), ranking, write-back.

NEEM -> ``odb_history:situation_history`` (one crossing) -> Steps -> PreferenceOracle -> ranking
-> ``NeemLogger.preference`` (an imagined preference the Prolog answers read).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from datetime import datetime

from oracle.algorithm.fast import PreferenceOracle
from oracle.algorithm.params import Hyperparameters
from oracle.algorithm.situation import Ranking
from oracle.chains import TaskCall, parse_call
from oracle.errors import LoggingError, NeemOracleError
from oracle.evaluation.replay import opening_tasks
from oracle.neem.writer import NeemLogger
from oracle.ontology import OdbOntology
from oracle.situations import call_of, check_call, option_of, steps_from_history
from oracle.timeline import time_of_day

#: Score written for options without similar history (the store and JSON need a finite number).
NO_HISTORY_SCORE = 1e9


@dataclass(frozen=True)
class NeemRanking:
    neem: str
    at: float
    time_of_day: str
    history: int
    ranking: Ranking
    calls: tuple[TaskCall, ...]
    chain: tuple[TaskCall, ...]
    milliseconds: float
    written: str | None
    note: str | None


def finite(score: float) -> float:
    return score if math.isfinite(score) else NO_HISTORY_SCORE


def rank_neem(
    bridge,  # oracle.bridge.Bridge  # noqa: ANN001
    ontology: OdbOntology,
    settings: Hyperparameters,
    available: list[str] | None = None,
    at: float | None = None,
    write: bool = True,
) -> NeemRanking:
    """Rank ``available`` (chain syntax) at ``at``, or else the NEEM's latest imagined situation."""
    if available:
        calls = [parse_call(text) for text in available]
        for call in calls:
            check_call(ontology, call, "available")
        when = at if at is not None else time.time()
    else:
        latest = bridge.latest_situation()
        if latest is None:
            raise NeemOracleError(f"NEEM {bridge.neem_id!r} has no imagined situation to rank; give the available calls")
        calls = [parse_call(text) for text in latest["available"]]
        when = float(latest["begin"])
    steps = steps_from_history(ontology, [row for row in bridge.history() if float(row["begin"]) < when])
    oracle = PreferenceOracle.from_settings(ontology.distances(), settings, opening_tasks(ontology)).fit(steps)
    part = time_of_day(datetime.fromtimestamp(when))
    started = time.perf_counter()
    ranking = oracle.rank([option_of(ontology, c) for c in calls], part)
    elapsed = (time.perf_counter() - started) * 1000
    written = note = None
    if write:
        logger = NeemLogger(bridge.store, ontology, bridge.neem_id)
        try:
            written = logger.preference([(call_of(ontology, t.option), finite(t.score)) for t in ranking], when)
        except LoggingError as error:
            note = f"ranking not written: {error}"
    return NeemRanking(bridge.neem_id, when, part, len(steps), ranking,
                       tuple(call_of(ontology, t.option) for t in ranking),
                       tuple(call_of(ontology, o) for o in ranking.chain()), elapsed, written, note)
