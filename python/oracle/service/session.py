"""One user's NEEM as the live service holds it: the logger writing it, the predictor fitted
on its history and updated per action, and what the robot announced since the last action.

Everything here runs on the service's one engine thread (engine.py); nothing is locked.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass
from datetime import datetime
from typing import Any, TypedDict

from oracle.algorithm.predictors import Predictor
from oracle.algorithm.records import RankedTask, Ranking
from oracle.answers import support_sentence
from oracle.chains import TaskCall, parse_call
from oracle.errors import LoggingError
from oracle.neem.tf import Pose
from oracle.neem.writer import LoggedAction, NeemLogger, check_performer
from oracle.past.autonomy import NO_PART
from oracle.past.modelogit import ranked_modes
from oracle.timeline import Instant, TimeValueError, parse_iso
from oracle.ontology import OdbOntology
from oracle.bridge import HistoryRow
from oracle.ranking import NeemRanker, finite, support_fields
from oracle.service.warm import Warm
from oracle.calls import call_of, check_call

#: The forward tree is built for the top suggestion only: the page and the API offer its chain
#: as the one workflow; the ranking itself does not depend on how many trees are built.
TREE_ROOTS = 1

Moment = datetime | float | Instant


@dataclass(frozen=True)
class Situation:
    """Tasks the robot announced as available, validated, with the time they hold."""

    calls: tuple[TaskCall, ...]
    when: Instant
    moment: Moment


class RankedEntry(TypedDict):
    """One ranked task of a situation answer (``NeemSession._entry`` says what each field is)."""

    rank: int
    task: str
    score: float
    support: int
    probability: float | None
    context_order: int | None
    context: list[str]
    focus: list[str]
    new: bool
    resumed: bool
    since: float | None
    situations: list[float]
    reason: str
    mode: str | None
    mode_support: dict[str, Any]


class SituationAnswer(TypedDict):
    """The service's answer to a situation: the NEEM, when (seconds, part of day), how many steps
    the predictor was fitted on, the ranking, the predicted chain with the usual mode of each of
    its steps and how long ranking took (ms)."""

    neem: str
    at: float
    time_of_day: str | None
    history: int
    ranking: list[RankedEntry]
    chain: list[str]
    chain_modes: list[str | None]
    ms: float


@dataclass(frozen=True)
class OpenAction:
    """An action whose begin was posted and whose end was not (kept in memory until its end)."""

    key: str
    call: TaskCall
    begin: Moment
    performed_by: str


class OutOfOrder(LoggingError):
    """A time before the end of the NEEM's last action: the NEEM's clock only goes forward."""


def moment_of(value: Any, what: str) -> Moment:
    """A time the API received: unix seconds, or ISO-8601 (naive: the logger's rule, UTC),
    within the range every store accepts."""
    moment = _moment(value, what)
    try:
        Instant.of(moment)
    except TimeValueError as error:
        raise LoggingError(f"{what}: {error}") from None
    return moment


def _moment(value: Any, what: str) -> Moment:
    if value is None:
        return time.time()
    if isinstance(value, Instant):
        return value  # a time read from the NEEM, with the part of day recorded with it
    if isinstance(value, bool):
        raise LoggingError(f"{what}: expected unix seconds or ISO-8601, got {value!r}")
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str):
        try:
            return parse_iso(value)
        except TimeValueError:
            pass
    raise LoggingError(f"{what}: expected unix seconds or ISO-8601 (2024-05-01T08:30), got {value!r}")


def pose_of(name: str, values: Sequence[float] | None) -> Pose | None:
    """The API's pose list, ``x, y, z`` or ``x, y, z, qx, qy, qz, qw`` in the robot's frame, as
    the logger's Pose (written to the NEEM's tf collection); LoggingError for any other length."""
    if values is None:
        return None
    if len(values) == 3:
        return Pose((values[0], values[1], values[2]))
    if len(values) == 7:
        return Pose((values[0], values[1], values[2]), (values[3], values[4], values[5], values[6]))
    raise LoggingError(f"pose of {name!r}: give x, y, z or x, y, z, qx, qy, qz, qw ({len(values)} numbers given)")


class NeemSession:
    """The live state of one NEEM. Validation happens before any write, so a refused request
    leaves both the NEEM and this object as they were."""

    def __init__(self, neem: str, logger: NeemLogger, ontology: OdbOntology, predictor: Predictor,
                 history: Sequence[HistoryRow]) -> None:
        self.neem = neem
        self.logger = logger
        self.ontology = ontology
        # the fit of a NEEM the CLI or an earlier service run ranked is kept (oracle.fitcache)
        # (never that of a temporary NEEM: it is wiped when the next session starts)
        #: The NEEM's ranking pipeline (oracle.ranking): its steps, fit, offers and breaks.
        self.ranker = NeemRanker(ontology, predictor, list(history), neem=neem, store=logger.store,
                                 clocked=logger.clocked, keep=not logger.store.neem(neem).temporary,
                                 idle_threshold=logger.idle_threshold)
        self.pending: Situation | None = None
        self.latest: SituationAnswer | None = None
        self.open: dict[str, OpenAction] = {}
        self.poses: dict[str, list[float]] = {}
        self.choice: dict[str, Any] | None = None
        self._keys = 0
        #: What the answers derive from the history alone, fitted once per history.
        self.warm = Warm()

    @property
    def predictor(self) -> Predictor:
        """The predictor fitted on the NEEM's history so far."""
        return self.ranker.predictor

    # -- validation ---------------------------------------------------------------------------
    def calls(self, texts: Sequence[str], where: str) -> tuple[TaskCall, ...]:
        calls = []
        for text in texts:
            call = parse_call(text)
            check_call(self.ontology, call, where)
            calls.append(call)
        return tuple(calls)

    def _check_time(self, when: Instant, what: str) -> None:
        last_end = self.ranker.last_end
        if last_end is not None and when.seconds < last_end:
            raise OutOfOrder(f"time goes backwards: {what} at {when.seconds:.3f} is before the end of the"
                               f" last action ({last_end:.3f}) in NEEM {self.neem!r}")

    # -- perception -------------------------------------------------------------------------
    def perceive(self, objects: Sequence[tuple[str, list[float] | None]], at: Any) -> list[str]:
        moment = moment_of(at, "at")
        when = Instant.of(moment)
        self._check_time(when, "perception")
        poses = []
        for name, pose in objects:
            if name not in self.ontology.objects:
                raise LoggingError(f"unknown object {name!r}")
            poses.append(pose_of(name, pose))
        iris = [self.logger.perceive(name, moment, pose) for (name, _), pose in zip(objects, poses)]
        self.logger.flush()
        for name, pose in objects:
            if pose is not None:
                self.poses[name] = pose
        return iris

    # -- situations ---------------------------------------------------------------------------
    def situation(self, available: Sequence[str], at: Any) -> tuple[Situation, Ranking, float]:
        """Validate and rank (no write): the ranking and how long ranking took (ms)."""
        found = self.offer(available, at)
        ranking, ms = self.rank(found)
        return found, ranking, ms

    def offer(self, available: Sequence[str], at: Any) -> Situation:
        """The situation the robot posts, validated (nothing ranked, nothing written)."""
        if not available:
            raise LoggingError("available must name at least one task, e.g. [\"pick(red_mug)\"]")
        calls = self.calls(available, "available")
        moment = moment_of(at, "at")
        when = Instant.of(moment)
        self._check_time(when, "situation")
        return Situation(calls, when, moment)

    def rank(self, situation: Situation) -> tuple[Ranking, float]:
        """The situation ranked (no write; whether it is written yet changes nothing): the
        ranking and how long ranking took (ms)."""
        decision = self.ranker.rank(situation.calls, situation.when, tree_roots=TREE_ROOTS)
        return decision.ranking, decision.ms

    def write_situation(self, situation: Situation, ranking: Ranking) -> str:
        """Log the situation as the imagined one and the ranking as the imagined preference,
        in one transaction; the returned IRI is the preference's."""
        self.logger.available(situation.calls, situation.moment)
        order = self.write_ranking(situation, ranking)
        self.imagined(situation)
        return order

    def write_imagined(self, situation: Situation) -> None:
        """Log the situation as the imagined one, committed (what the answer waits for)."""
        self.logger.available(situation.calls, situation.moment)
        self.logger.flush()
        self.imagined(situation)

    def write_ranking(self, situation: Situation, ranking: Ranking) -> str:
        """Log the ranking as the imagined preference (the service writes it after the answer:
        it is derived, and nothing the robot waits for); its IRI."""
        order = self.logger.preference(
            [(call_of(self.ontology, t.option), finite(t.score)) for t in ranking], situation.moment)
        self.logger.flush()
        return order

    def imagined(self, situation: Situation) -> None:
        self.pending = situation
        self.ranker.imagine(situation.calls, situation.when.seconds)

    def describe(self, situation: Situation, ranking: Ranking, ms: float) -> SituationAnswer:
        calls = [str(call_of(self.ontology, t.option)) for t in ranking]
        chain = [str(call_of(self.ontology, o)) for o in ranking.chain()]
        usual, chain_modes = ranked_modes(self.ranker.modes, calls, chain, situation.when.part_of_day,
                                          self.warm.modes(self.ranker))
        ranked = []
        for t, call, mode in zip(ranking, calls, usual, strict=True):
            entry = self._entry(t, call)
            entry["mode"], entry["mode_support"] = mode.mode, {"context": mode.context, "counts": mode.counts}
            ranked.append(entry)
        self.latest = SituationAnswer(
            neem=self.neem, at=situation.when.seconds, time_of_day=situation.when.part_of_day,
            history=self.predictor.n_steps_, ranking=ranked, chain=chain, chain_modes=chain_modes,
            ms=round(ms, 3),
        )
        return self.latest

    def usual_mode(self, call: TaskCall | str, at: float | None) -> str | None:
        """Who usually does ``call`` (None: no action of its task is known), at ``at`` (None: the
        latest ranking's part of the day)."""
        latest = self.latest
        part = (latest["time_of_day"] if latest is not None else None) if at is None else Instant.of(at).part_of_day
        text = str(call if isinstance(call, TaskCall) else parse_call(call))  # one spelling: pour(a, b)
        return self.ranker.modes.usual(text, part if part is not None and self.logger.clocked else NO_PART).mode

    def _entry(self, task: RankedTask, call: str) -> RankedEntry:
        """One ranked task as the API answers it: ``support`` is how many past situations back
        it (the thesis oracle: |H(s_o)|; the routine predictor: how often the user did it after
        the same exact context), ``situations`` when the latest of those began (at most 5),
        ``focus`` the objects in hand it uses, ``new`` whether it is newly offered, ``resumed``
        whether, after a break, it picks up where the user left off, ``since`` how many seconds
        ago the user last did it (where the clock weighed the ranking), ``reason`` the same in a
        few words."""
        fields = support_fields(task)
        begins = self.ranker.begins
        entry = RankedEntry(rank=task.rank, task=call, score=finite(task.score), support=task.n_similar,
                            probability=fields.get("probability"), context_order=fields.get("context_order"),
                            context=fields.get("context", []), focus=fields.get("focus", []),
                            new=fields.get("new", False), resumed=fields.get("resumed", False), since=fields.get("since"),
                            situations=[begins[p] for p in fields.get("situations", []) if p < len(begins)], reason="",
                            mode=None, mode_support={})
        entry["reason"] = support_sentence({**entry, "done": task.option in self.ranker.done_before.done})
        return entry

    # -- actions ------------------------------------------------------------------------------
    def begin(self, call_text: str, at: Any, performed_by: str, key: str | None) -> OpenAction:
        call = self.calls([call_text], "call")[0]
        moment = moment_of(at, "at")
        self._check_time(Instant.of(moment), f"action {call}")
        check_performer(performed_by)
        if key is None:
            self._keys += 1
            key = f"a{self._keys}"
        if key in self.open:
            raise LoggingError(f"action {key!r} has already begun in NEEM {self.neem!r}")
        action = OpenAction(key, call, moment, performed_by)
        self.open[key] = action
        return action

    def end(self, key: str | None, call_text: str | None, at: Any, state: str | None = None) -> LoggedAction:
        if key is None:
            matches = [a for a in self.open.values() if call_text is not None and str(a.call) == str(parse_call(call_text))]
            if call_text is None:
                raise LoggingError("phase end needs the id the begin answered (or the open action's call)")
            if len(matches) != 1:
                raise LoggingError(f"no single open action {call_text!r} to end; give its id")
            key = matches[0].key
        action = self.open.get(key)
        if action is None:
            raise LoggingError(f"no open action {key!r} in NEEM {self.neem!r}")
        logged = self.log(str(action.call), action.begin, at, action.performed_by, state)
        del self.open[key]
        return logged

    def log(self, call_text: str, begin: Any, end: Any, performed_by: str = "robot", state: str | None = None) -> LoggedAction:
        """Log an executed action (the logger inserts the idle action before a long gap) and
        teach the predictor the same steps the NEEM's history will show."""
        call = self.calls([call_text], "call")[0]
        start = moment_of(begin, "begin")
        stop = moment_of(end, "end") if end is not None else start
        self._check_time(Instant.of(start), f"action {call}")
        logged = self.logger.action(call, start, stop, performed_by=performed_by, state=state)
        self.logger.flush()
        self.ranker.acted(call, logged.begin, logged.end, logged.part_of_day, after_idle=logged.idle is not None,
                          performed_by=performed_by)
        self.pending = None
        return logged
