"""The oracle in the system: history from the NEEM (through Prolog), ranking, write-back.

``NeemRanker`` is the one ranking pipeline: ``rank`` builds one per call, the service holds one
per NEEM and extends it as the robot logs (oracle.service.session).

NEEM -> ``odb_history:situation_history`` (one crossing) -> Steps -> the chosen predictor (its fit
kept between calls, oracle.fitcache) -> ranking -> ``NeemLogger.preference`` (an imagined preference the Prolog answers read).

The answers read the written rank (1 = best) and show the score; for every predictor the score is
lower-is-better: the thesis oracle writes its eq. 4.12 distance, the routine predictor -log2 of its
probability (docs/algorithm.md).
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from oracle.algorithm.chaining import Afterwards, chain_ahead, reranks
from oracle.algorithm.params import Hyperparameters
from oracle.algorithm.predictors import DEFAULT, Predictor
from oracle.algorithm.predictors import make_predictor as make_named
from oracle.algorithm.records import Option, RankedTask, Ranking, Step, local_name
from oracle.chains import TaskCall, parse_call
from oracle.errors import LoggingError, NeemOracleError
from oracle.fitcache import FitCache
from oracle.historycache import HistoryCache
from oracle.calls import DoneBefore, call_of, check_call, history_steps, idle_step, opening_tasks, option_of
from oracle.neem.writer import NeemLogger
from oracle.ontology import OdbOntology
from oracle.past.autonomy import NO_PART, ModeCounts, Performed, UsualMode, modes_from_rows
from oracle.past.modelogit import ranked_modes
from oracle.timeline import IDLE_THRESHOLD_S, Instant, clock, has_clock, is_idle_gap, now, part_of_day_at

if TYPE_CHECKING:
    from oracle.algorithm.prior import Prior
    from oracle.bridge import Bridge, HistoryRow, HistoryView, LatestSituation
    from oracle.store import Store

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
    #: Who usually does each ranked task, and each step of the chain (oracle.past.autonomy).
    usual: tuple[UsualMode, ...] = ()
    chain_modes: tuple[str | None, ...] = ()
    #: Of ``history``, the idle steps: the breaks the NEEM logged as idle actions (``neems``
    #: counts them among its actions), and whether the last is the break since the last action
    #: (not logged yet: the logger writes it with the next action).
    breaks: int = 0
    pause: bool = False
    #: Per ranked task, what the shared prior says of it ("people usually do this after ..."), or
    #: None where the prior did not carry it (always None without a prior).
    people: tuple[str | None, ...] = ()


def make_predictor(ontology: OdbOntology, settings: Hyperparameters | None = None, method: str = DEFAULT,
                   prior: Prior | None = None) -> Predictor:
    """The predictor ``method`` names (oracle.algorithm.predictors: ``personal``, the default,
    ``pooled``, ``routine`` or ``thesis``) for ``ontology``'s tasks and distances, unfitted; ``settings`` (default: the
    thesis's Table 4.2) apply to ``thesis``; ``prior``: the shared prior a predictor that takes one ranks with.
    What ``rank``, the service and the import fit."""
    model = make_named(method, ontology.distances(), opening_tasks(ontology), settings or Hyperparameters())
    use = getattr(model, "use_prior", None)
    if prior is not None and use is not None:
        use(prior)
    return model


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
    prior: Prior | None = None,
) -> NeemRanking:
    """Rank ``available`` (chain syntax) at ``at`` (default: now), or else the NEEM's latest
    imagined situation, at the part of day recorded with it (oracle.timeline's rule); a NEEM
    that imagined nothing (an import of chains without available sets) gets the actions done so
    far ranked, as ``available``, the offer its history steps get (oracle.calls.steps_from_history).
    In a NEEM without a clock, times are positions with no part of the day, and "now" is the position
    after the last action. The fit is kept in ``cache`` (default: the user's, oracle.fitcache)
    and extended by the actions logged since; so is the history read (``histories``, default:
    the user's, oracle.historycache)."""
    view = (histories or HistoryCache.default()).view(bridge)
    info = bridge.store.neem(bridge.neem_id)
    clocked = has_clock(info.meta)
    calls, instant, offered = _offer(bridge.neem_id, ontology, view, available, at, clocked)
    ranker = NeemRanker(ontology, make_predictor(ontology, settings, method, prior),
                        [row for row in view.rows if float(row["begin"]) < instant.seconds],
                        neem=bridge.neem_id, store=bridge.store, clocked=clocked, keep=not info.temporary, fits=cache)
    decision = ranker.rank(calls, instant)
    ranking = decision.ranking
    written = note = None
    if write:
        logger = NeemLogger(bridge.store, ontology, bridge.neem_id)
        try:
            written = logger.preference([(call_of(ontology, t.option), finite(t.score)) for t in ranking], instant)
        except LoggingError as error:
            note = f"ranking not written: {error}"
    if offered is not None:
        note = offered if note is None else f"{offered}; {note}"
    ranked = tuple(call_of(ontology, t.option) for t in ranking)
    chain = tuple(call_of(ontology, o) for o in ranking.chain())
    usual, chain_modes = ranked_modes(ranker.modes, [str(c) for c in ranked], [str(c) for c in chain],
                                      instant.part_of_day)
    return NeemRanking(bridge.neem_id, instant.seconds, instant.part_of_day, len(ranker.steps), ranking, ranked,
                       chain, decision.ms, written, note, method, tuple(usual), tuple(chain_modes),
                       sum(1 for step in ranker.steps if step.idle), ranker.idle_fitted,
                       tuple(people_words(ranker.predictor, ranking)))


def people_words(predictor: Predictor, ranking: Ranking) -> list[str | None]:
    """What the shared prior says of each ranked task (``PersonalOracle.usually``): "people
    usually do this after X" (the user's own last task, X, the context other people did it after),
    "people often do this" (order 0), or None."""
    from oracle.algorithm.prior import IDLE

    usually = getattr(predictor, "usually", None)
    if usually is None:
        return [None] * len(ranking.tasks)
    tokens = getattr(predictor, "_tokens", [])
    words: list[str | None] = []
    for task in ranking.tasks:
        found = usually(task.option)
        if found is None:
            words.append(None)
        elif found[0] == 0:
            words.append(f"people often do this ({found[1]:.0%} of what they do)")
        else:
            after = ", ".join("a break" if t == IDLE else t for t in tokens[len(tokens) - found[0]:])
            words.append(f"people usually do this after {after} ({found[1]:.0%})")
    return words


def keep_neem(store: Store, ontology: OdbOntology, neem: str, settings: Hyperparameters | None = None,
              method: str = DEFAULT) -> None:
    """Read and fit what the first ``rank`` of NEEM ``neem`` needs, and keep both in the store
    (oracle.historycache, oracle.fitcache): the import calls it, so that rank and the service
    start from what was kept and read only what is logged after. A temporary NEEM keeps nothing,
    nor does a store that cannot tell what was added since (MongoDB: a rank reads it whole)."""
    from oracle.bridge import Bridge

    info = store.neem(neem)
    if info.temporary or store.append_mark(neem) is None:
        return  # nothing may outlive it, or a store that cannot tell what was added (MongoDB)
    bridge = Bridge(store, neem, ontology)
    try:
        view = HistoryCache.default().view(bridge)
    finally:
        bridge.close()
    before = float(view.latest["begin"]) if view.latest is not None else math.inf  # what rank fits
    NeemRanker(ontology, make_predictor(ontology, settings, method),
               [row for row in view.rows if float(row["begin"]) < before], neem=neem, store=store,
               clocked=has_clock(info.meta))


def _offer(neem: str, ontology: OdbOntology, view: HistoryView, available: list[str] | None,
           at: Instant | None, clocked: bool) -> tuple[list[TaskCall], Instant, str | None]:
    """What a ``rank`` ranks and when: the calls given (at ``at``, default now; on the sequence
    clock the position after the last action), else the latest imagined situation at its
    begin and recorded part of day, else the actions done before ``at``; and a note saying so
    in the last case."""
    history = view.rows
    latest = None if available else view.latest
    offered = None
    if not available and latest is None:
        before = at.seconds if at is not None else math.inf   # what was done before the decision
        available = list(dict.fromkeys(row["call"] for row in history
                                       if row["call"] != "idle" and float(row["begin"]) < before))
        if not available:
            raise NeemOracleError(f"NEEM {neem!r} has no imagined situation and no action to rank; "
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
        return calls, instant, offered
    assert latest is not None  # no available calls: the NEEM's latest situation, found above
    return [parse_call(text) for text in latest["available"]], latest_instant(latest, clocked), None


def latest_instant(latest: LatestSituation, clocked: bool) -> Instant:
    """When the latest imagined situation (``Bridge.latest_situation``) holds: its begin, at the
    part of day recorded with it (oracle.timeline's rule where none was; none without a clock)."""
    begin = float(latest["begin"])
    recorded = latest.get("part") if latest.get("part") != "none" else None
    return Instant(begin, (recorded or part_of_day_at(begin)) if clocked else None)


@dataclass(frozen=True)
class Decision:
    """A ranking of one decision: the ranking, the instant it is for and how long the
    predictor took (ms; the fit of the steps before it not counted)."""

    ranking: Ranking
    when: Instant
    ms: float


@dataclass(frozen=True)
class Imagined:
    """The situation imagined since the last action: its calls and when it began (seconds)."""

    calls: tuple[TaskCall, ...]
    seconds: float


class NeemRanker:
    """One NEEM's ranking pipeline, the same for ``rank``, the answers and the service: the
    oracle's steps of its history (``situation_history`` rows), the predictor fitted on them
    (kept between calls by ``fits``, oracle.fitcache), and, as the NEEM grows, the step each
    logged action adds, with the offer it had. The two rules a decision needs live here once:
    the idle step before a decision that follows a break (fitted before the logger writes it,
    as the replay ranks), and which imagined situation counts as an action's offer (the
    latest one that began after the previous action and not after this one,
    odb_history:situation_history's rule; else the actions done so far)."""

    def __init__(self, ontology: OdbOntology, predictor: Predictor, rows: Sequence[HistoryRow], *,
                 neem: str, store: Store, clocked: bool, keep: bool = True, idle_threshold: float = IDLE_THRESHOLD_S,
                 fits: FitCache | None = None) -> None:
        self.ontology = ontology
        self.clocked = clocked
        self.idle_threshold = idle_threshold
        #: The steps fitted so far, and when each began (the predictor's history positions: what
        #: a ranking's supporting past situations are shown as).
        steps, done = history_steps(ontology, rows, clocked)
        self.steps: list[Step] = steps
        self.begins: list[float] = [float(row["begin"]) for row in rows]
        self.predictor: Predictor = (fits or FitCache.default()).fitted(predictor, self.steps, store.location, neem, keep=keep,
                                                             kept=store)
        prior = getattr(predictor, "prior", None)
        if prior is not None:  # a kept fit comes back without the process's prior (never kept with it)
            self.predictor.use_prior(prior)
        #: What the user did so far: the offer of an action logged without an imagined
        #: situation, and which ranked tasks were done before (made with the steps).
        self.done_before: DoneBefore = done
        #: What was offered after each option done: what the predicted chain may continue with.
        self.afterwards = Afterwards(self.steps)
        ends = [float(row["end"] if row.get("end") is not None else row["begin"]) for row in rows]
        #: The end of the last action: nothing may be logged before it.
        self.last_end: float | None = max(ends) if ends else None
        #: The begin of the last action: a situation counts for the next action only after it.
        self.prev_begin: float | None = max(self.begins) if self.begins else None
        #: Whether the last step is the idle step of the current break, fitted before its idle
        #: action is logged (the logger writes it only with the next action).
        self.idle_fitted = False
        self.imagined: Imagined | None = None
        #: Who performed the actions so far, counted (oracle.past.autonomy): who usually does
        #: each ranked task.
        self.modes: ModeCounts = modes_from_rows(rows)

    def options(self, calls: Sequence[TaskCall]) -> list[Option]:
        return [option_of(self.ontology, call) for call in calls]

    def rank(self, calls: Sequence[TaskCall], when: Instant, *, tree_roots: int | None = None) -> Decision:
        """Rank ``calls`` at ``when`` (never written; the predictor sees the break before it);
        ``tree_roots``: the forward trees built, of a predictor that chains by its tree (the
        thesis oracle; the routine predictors build none, their chain is re-ranked)."""
        self._fit_break(when.seconds)
        options = self.options(calls)
        rechained = self.predictor if reranks(self.predictor) else None
        if rechained is not None:
            tree_roots = 0  # its chain is re-ranked: no forward tree is read
        started = time.perf_counter()
        at = when.seconds if self.clocked else None
        ranking = (self.predictor.rank(options, when.part_of_day, at=at) if tree_roots is None
                   else self.predictor.rank(options, when.part_of_day, tree_roots=tree_roots, at=at))
        ms = (time.perf_counter() - started) * 1000
        if rechained is not None:  # the routine predictors' chain: re-ranked after each step taken as done
            length = 1 + int(rechained.event_horizon_forward)
            chain = chain_ahead(rechained, ranking, options, self.afterwards, when.part_of_day, at, length)
            ranking = dataclasses.replace(ranking, ahead=chain)
        return Decision(ranking, when, ms)

    def imagine(self, calls: Sequence[TaskCall], seconds: float) -> None:
        """The robot imagined ``calls`` available at ``seconds`` (the next action's offer if it counts)."""
        self.imagined = Imagined(tuple(calls), seconds)

    def acted(self, call: TaskCall, begin: float, end: float, part_of_day: str | None, *, after_idle: bool,
              performed_by: str | None = None) -> None:
        """The step an action logged from ``begin`` to ``end`` adds (``after_idle``: the logger
        wrote an idle action before it), as the NEEM's history will show it; ``performed_by``
        (chains.MODES) is counted among the user's modes."""
        if after_idle and self.last_end is not None:
            if not self.idle_fitted:
                self._fit(idle_step(self.ontology, clock(self.last_end)), self.last_end)
            self.prev_begin = self.last_end
        elif self.idle_fitted:
            # the action began before the break the predictor was told of (within the idle gap
            # of the last action): the NEEM holds no idle action, so neither may the predictor
            self.steps.pop()
            self.begins.pop()
            self.predictor = self.predictor.fit(self.steps)
            self.afterwards = Afterwards(self.steps)
        self.idle_fitted = False
        imagined = self.imagined
        counts = (imagined is not None and imagined.seconds <= begin
                  and (self.prev_begin is None or imagined.seconds > self.prev_begin))
        options = (tuple(self.options(sorted(set(imagined.calls), key=str))) if counts and imagined
                   else self.done_before.offer())
        option = option_of(self.ontology, call)
        self._fit(Step(option.task, option.target, option.reference, options, part_of_day, False, str(call),
                       begin if self.clocked else None), begin)
        self.last_end = end
        self.prev_begin = begin
        self.imagined = None
        if performed_by is not None:
            self.modes.add(Performed(str(call), part_of_day or NO_PART, performed_by))

    def _fit(self, step: Step, begin: float) -> None:
        self.predictor.partial_fit(step)
        self.steps.append(step)
        self.begins.append(begin)
        self.afterwards.add(step)
        if not step.idle:
            self.done_before.add(Option(step.task, step.target, step.reference))

    def _fit_break(self, now: float) -> None:
        """The idle step before a decision after an idle gap since the last action's end: the
        NEEM will hold it once the next action is logged; the predictor must see it now."""
        if (not self.idle_fitted and self.steps and not self.steps[-1].idle
                and is_idle_gap(self.last_end, now, self.idle_threshold)):
            assert self.last_end is not None
            self._fit(idle_step(self.ontology, clock(self.last_end)), self.last_end)  # as the logger will date it
            self.idle_fitted = True
