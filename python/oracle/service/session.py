"""One user's NEEM as the live service holds it: the logger writing it, the predictor fitted
on its history and updated per action, and what the robot announced since the last action.

Everything here runs on the service's one engine thread (engine.py); nothing is locked.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass
from datetime import datetime
from typing import Any

from oracle.algorithm.params import Hyperparameters
from oracle.algorithm.predictors import DEFAULT, Predictor
from oracle.algorithm.predictors import make_predictor as make_named
from oracle.algorithm.records import Option, RankedTask, Ranking, Step
from oracle.answers import support_sentence
from oracle.chains import TaskCall, parse_call
from oracle.errors import LoggingError
from oracle.fitcache import FitCache
from oracle.neem.tf import Pose
from oracle.neem.writer import LoggedAction, NeemLogger, check_performer
from oracle.timeline import Instant, TimeValueError, clock, is_idle_gap
from oracle.ontology import OdbOntology
from oracle.ranking import finite, support_fields
from oracle.calls import DoneBefore, call_of, check_call, idle_step, opening_tasks, option_of, steps_from_history

#: The forward tree is built for the top suggestion only: the page and the API offer its chain
#: as the one workflow; the ranking itself does not depend on how many trees are built.
TREE_ROOTS = 1

Moment = datetime | float


@dataclass(frozen=True)
class Situation:
    """Tasks the robot announced as available, validated, with the time they hold."""

    calls: tuple[TaskCall, ...]
    when: Instant
    moment: Moment


@dataclass(frozen=True)
class OpenAction:
    """An action whose begin was posted and whose end was not (kept in memory until its end)."""

    key: str
    call: TaskCall
    begin: Moment
    performed_by: str


class OutOfOrder(LoggingError):
    """A time before the end of the NEEM's last action: the NEEM's clock only goes forward."""


def make_predictor(ontology: OdbOntology, settings: Hyperparameters, method: str = DEFAULT) -> Predictor:
    """The predictor a session fits: ``method`` by name (oracle.algorithm.predictors; the
    settings apply to ``thesis``), the same one ``rank`` uses by default."""
    return make_named(method, ontology.distances(), opening_tasks(ontology), settings)


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
    if isinstance(value, bool):
        raise LoggingError(f"{what}: expected unix seconds or ISO-8601, got {value!r}")
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str):
        try:
            return datetime.fromisoformat(value.replace("Z", "+00:00"))
        except ValueError:
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
                 history: Sequence[dict[str, Any]]) -> None:
        self.neem = neem
        self.logger = logger
        self.ontology = ontology
        #: The steps fitted so far, and when each began (the predictor's history positions: what
        #: a ranking's supporting past situations are shown as).
        self.steps: list[Step] = steps_from_history(ontology, history, logger.clocked)
        self.begins: list[float] = [float(row["begin"]) for row in history]
        # the fit of a NEEM the CLI or an earlier service run ranked is kept (oracle.fitcache)
        # (never that of a temporary NEEM: it is wiped when the next session starts)
        self.predictor = FitCache.default().fitted(predictor, self.steps, logger.store.location, neem,
                                                   keep=not logger.store.neem(neem).temporary)
        #: What the user did so far: the offer of an action logged without an imagined
        #: situation, as the history read gives it, and which ranked tasks were done before.
        self.done_before = DoneBefore()
        for step in self.steps:
            if not step.idle:
                self.done_before.add(Option(step.task, step.target, step.reference))
        ends = [float(row["end"]) for row in history]
        begins = [float(row["begin"]) for row in history]
        #: The logger's clock: nothing may be logged before the end of the last action.
        self.last_end: float | None = max(ends) if ends else None
        #: Begin of the last logged action: a situation counts for the next action only when it
        #: came after it (odb_history:situation_history's rule).
        self.prev_begin: float | None = max(begins) if begins else None
        #: The idle step of the current pause is fitted before its idle action is logged: by the
        #: first situation after an idle gap, ranked as the replay ranks it (the logger writes the
        #: idle action only with the next action, which then fits nothing more).
        self.idle_fitted = False
        self.pending: Situation | None = None
        self.latest: dict[str, Any] | None = None
        self.open: dict[str, OpenAction] = {}
        self.poses: dict[str, list[float]] = {}
        self.choice: dict[str, Any] | None = None
        self._keys = 0

    # -- validation ---------------------------------------------------------------------------
    def calls(self, texts: Sequence[str], where: str) -> tuple[TaskCall, ...]:
        calls = []
        for text in texts:
            call = parse_call(text)
            check_call(self.ontology, call, where)
            calls.append(call)
        return tuple(calls)

    def _check_time(self, when: Instant, what: str) -> None:
        if self.last_end is not None and when.seconds < self.last_end:
            raise OutOfOrder(f"time goes backwards: {what} at {when.seconds:.3f} is before the end of the"
                               f" last action ({self.last_end:.3f}) in NEEM {self.neem!r}")

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
        if not available:
            raise LoggingError("available must name at least one task, e.g. [\"pick(red_mug)\"]")
        calls = self.calls(available, "available")
        moment = moment_of(at, "at")
        when = Instant.of(moment)
        self._check_time(when, "situation")
        self._fit_break(when.seconds)
        started = time.perf_counter()
        ranking = self.predictor.rank([option_of(self.ontology, c) for c in calls], when.part_of_day,
                                      tree_roots=TREE_ROOTS, at=when.seconds if self.logger.clocked else None)
        return Situation(calls, when, moment), ranking, (time.perf_counter() - started) * 1000

    def _fit(self, step: Step, begin: float) -> None:
        self.predictor.partial_fit(step)
        self.steps.append(step)
        self.begins.append(begin)
        if not step.idle:
            self.done_before.add(Option(step.task, step.target, step.reference))

    def _fit_break(self, now: float) -> None:
        """The idle step before a situation posted an idle gap after the last action's end: the
        NEEM will hold it once the next action is logged; the predictor must see it now."""
        if not self.idle_fitted and self.last_end is not None and is_idle_gap(self.last_end, now, self.logger.idle_threshold):
            self._fit(idle_step(self.ontology, clock(self.last_end)), self.last_end)
            self.idle_fitted = True

    def write_situation(self, situation: Situation, ranking: Ranking) -> str:
        """Log the situation as the imagined one and the ranking as the imagined preference,
        in one transaction; the returned IRI is the preference's."""
        self.logger.available(situation.calls, situation.moment)
        order = self.logger.preference(
            [(call_of(self.ontology, t.option), finite(t.score)) for t in ranking], situation.moment)
        self.logger.flush()
        self.pending = situation
        return order

    def describe(self, situation: Situation, ranking: Ranking, ms: float) -> dict[str, Any]:
        calls = [str(call_of(self.ontology, t.option)) for t in ranking]
        self.latest = {
            "neem": self.neem, "at": situation.when.seconds, "time_of_day": situation.when.part_of_day,
            "history": self.predictor.n_steps_,
            "ranking": [self._entry(t, call) for t, call in zip(ranking, calls, strict=True)],
            "chain": [str(call_of(self.ontology, o)) for o in ranking.chain()],
            "ms": round(ms, 3),
        }
        return self.latest

    def _entry(self, task: RankedTask, call: str) -> dict[str, Any]:
        """One ranked task as the API answers it: ``support`` is how many past situations back
        it (the thesis oracle: |H(s_o)|; the routine predictor: how often the user did it after
        the same exact context), ``situations`` when the latest of those began (at most 5),
        ``focus`` the objects in hand it uses, ``new`` whether it is newly offered, ``resumed``
        whether, after a break, it picks up where the user left off, ``since`` how many seconds
        ago the user last did it (where the clock weighed the ranking), ``reason`` the same in a
        few words."""
        fields = support_fields(task)
        entry: dict[str, Any] = {"rank": task.rank, "task": call, "score": finite(task.score), "support": task.n_similar,
                                 "probability": fields.get("probability"), "context_order": fields.get("context_order"),
                                 "context": fields.get("context", []), "focus": fields.get("focus", []),
                                 "new": fields.get("new", False), "resumed": fields.get("resumed", False),
                                 "since": fields.get("since"),
                                 "situations": [self.begins[p] for p in fields.get("situations", []) if p < len(self.begins)]}
        entry["reason"] = support_sentence({**entry, "done": task.option in self.done_before.done})
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

    def end(self, key: str | None, call_text: str | None, at: Any) -> LoggedAction:
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
        logged = self.log(str(action.call), action.begin, at, action.performed_by)
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
        if logged.idle is not None and self.last_end is not None:
            if not self.idle_fitted:
                self._fit(idle_step(self.ontology, clock(self.last_end)), self.last_end)
            self.prev_begin = self.last_end
        elif self.idle_fitted:
            # the action began before the break the predictor was told of (within the idle gap
            # of the last action): the NEEM holds no idle action, so neither may the predictor
            self.steps.pop()
            self.begins.pop()
            self.predictor = self.predictor.fit(self.steps)
        self.idle_fitted = False
        pending = self.pending
        counts = (pending is not None and pending.when.seconds <= logged.begin
                  and (self.prev_begin is None or pending.when.seconds > self.prev_begin))
        options = (tuple(option_of(self.ontology, c) for c in sorted(set(pending.calls), key=str)) if counts and pending
                   else self.done_before.offer())
        option = option_of(self.ontology, call)
        self._fit(Step(option.task, option.target, option.reference, options, logged.part_of_day, False, str(call),
                       logged.begin if self.logger.clocked else None), logged.begin)
        self.last_end = logged.end
        self.prev_begin = logged.begin
        self.pending = None
        return logged
